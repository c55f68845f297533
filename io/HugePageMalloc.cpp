// Implements io/HugePageMalloc.h. Why: on the shared mandible under a kernel in "madvise" mode
// (this project's 2-core machines), a whole run spent 22 s of system time in 2.7 M page faults,
// and its user time suffered TLB misses over gigabytes of 4 KB pages; with glibc's hugetlb
// tunable the faults were 0.78 M and the run 112 -> 90 s (medians of alternating pairs), the same
// mesh, the same peak (docs/BENCHMARKS.md, session 41).
#include "io/HugePageMalloc.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace jawmesh {
namespace {
constexpr const char* kTunable = "glibc.malloc.hugetlb";

/// The value the tunables give glibc.malloc.hugetlb, or empty when they do not set it.
std::string hugetlbValue(const char* tunables) {
    if (!tunables) return {};
    std::istringstream in(tunables);
    std::string item, value;
    while (std::getline(in, item, ':'))
        if (item.rfind(std::string(kTunable) + "=", 0) == 0) value = item.substr(std::strlen(kTunable) + 1);
    return value;
}
}  // namespace

std::string activeHugePageMode(const std::string& fileText) {
    const std::size_t opening = fileText.find('['), closing = fileText.find(']', opening);
    if (opening == std::string::npos || closing == std::string::npos) return {};
    return fileText.substr(opening + 1, closing - opening - 1);
}

std::optional<std::string> tunablesForHugePages(const std::string& mode, const char* current) {
    if (mode != "madvise" || !hugetlbValue(current).empty()) return std::nullopt;
    const std::string setting = std::string(kTunable) + "=1";
    if (!current || !*current) return setting;
    return std::string(current) + ":" + setting;
}

std::string kernelHugePageMode() {
    std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
    std::stringstream text;
    text << file.rdbuf();
    return activeHugePageMode(text.str());
}

void reexecWithHugePageMalloc(char** argv) {
    const char* current = std::getenv("GLIBC_TUNABLES");
    const std::optional<std::string> tunables = tunablesForHugePages(kernelHugePageMode(), current);
    if (!tunables) return;
    const std::optional<std::string> before = current ? std::optional<std::string>(current) : std::nullopt;
    if (setenv("GLIBC_TUNABLES", tunables->c_str(), 1) != 0) return;
    execv("/proc/self/exe", argv);
    // only on failure: go on with the pages as they are, and the environment that says so
    if (before) setenv("GLIBC_TUNABLES", before->c_str(), 1);
    else unsetenv("GLIBC_TUNABLES");
}

bool mallocAdvisesHugePages() {
    const std::string value = hugetlbValue(std::getenv("GLIBC_TUNABLES"));
    return value == "1" || value == "2";
}

}  // namespace jawmesh
