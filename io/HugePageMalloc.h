// Transparent huge pages for glibc's malloc: the process re-executes itself once with the glibc
// tunable that asks for them, where the kernel gives them only on request.
#pragma once

#include <optional>
#include <string>

namespace jawmesh {

/// The active mode of /sys/kernel/mm/transparent_hugepage/enabled ("always", "madvise" or
/// "never": the word in brackets of `fileText`); empty when there is none.
std::string activeHugePageMode(const std::string& fileText);

/// This kernel's mode (activeHugePageMode of the file); empty when the file is not there.
std::string kernelHugePageMode();

/// The value GLIBC_TUNABLES should have for malloc to advise huge pages (`glibc.malloc.hugetlb=1`
/// added to `current`, which may be null), or nothing when no change is needed: the kernel's
/// mode is not "madvise" (with "always" every large mapping gets them anyway, with "never" none
/// can), or `current` already sets glibc.malloc.hugetlb (the user's choice; `=0` turns it off).
std::optional<std::string> tunablesForHugePages(const std::string& mode, const char* current);

/// Re-executes this binary (/proc/self/exe, the same arguments and process id) with the tunables
/// of tunablesForHugePages when they differ from this process's; returns when they do not, or
/// when the re-execution fails (the run goes on as before). Call before a command does its work
/// (main does, once the arguments are checked): glibc reads its tunables only at start-up.
void reexecWithHugePageMalloc(char** argv);

/// Whether this process's malloc was told to advise huge pages (GLIBC_TUNABLES holds
/// glibc.malloc.hugetlb=1 or =2): recorded in run.json beside the timings.
bool mallocAdvisesHugePages();

}  // namespace jawmesh
