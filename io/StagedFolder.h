// Multi-file outputs (a run's jaw folder, carved level sets, a report) are written into a hidden
// staging folder beside their destination and moved into place only when complete, so a failed or
// interrupted command leaves no partial set of files. Each file is also written atomically
// (io/AtomicFile.h); this adds the same guarantee for the set.
#pragma once

#include <string>

namespace jawmesh {

/// Usage: `StagedFolder staged(dest); write under staged.path(); staged.commit();`
/// Without commit() (an exception, a cancel) the destructor removes the staging folder and the
/// empty parent folders the constructor had to create, so nothing of the attempt is left.
class StagedFolder {
public:
    /// Stages destDir in "<parent of destDir>/.<name of destDir>.partial-<pid>" (the same file
    /// system, so committing is renames). Missing parents are created.
    /// Throws Error naming destDir when the staging folder cannot be created.
    explicit StagedFolder(const std::string& destDir);
    ~StagedFolder();
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;

    /// Where to write: stands for destDir.
    const std::string& path() const { return staging_; }

    enum class Mode {
        Replace,  ///< destDir becomes exactly what was staged (a folder jawmesh owns: a run's jaw folder)
        Merge,    ///< staged files replace files of the same relative path; other files in destDir stay
    };

    /// Moves what was staged into destDir (one rename when destDir does not exist; Replace: see
    /// replaceFolder(); Merge: one rename per file). Throws Error naming the file when a rename fails.
    void commit(Mode mode);

private:
    std::string dest_;
    std::string staging_;
    std::string createdTop_;  ///< highest parent folder the constructor created, empty if none
    bool committed_ = false;
};

/// Replaces destDir by completeDir (same file system): the old destDir, if any, is moved aside to
/// "<completeDir>.old", completeDir renamed into place, the old one removed. A kill in between leaves
/// no folder or the complete new one at destDir, never a mix. Throws Error when a rename fails.
void replaceFolder(const std::string& completeDir, const std::string& destDir);

}  // namespace jawmesh
