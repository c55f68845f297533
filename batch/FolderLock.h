// One coordinator per batch output folder: two local batches (or a batch and a --slurm
// preparation) writing the same manifest would lose each other's records.
#pragma once

#include <string>

namespace jawmesh {

/// Holds an exclusive flock on <dir>/.batch.lock (created with its folder) until destroyed; the
/// kernel drops it when the process dies, so a killed batch never leaves the folder locked.
class FolderLock {
public:
    /// Throws Error naming the folder when another process holds the lock or it cannot be created.
    explicit FolderLock(const std::string& dir);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

private:
    int fd_ = -1;
};

}  // namespace jawmesh
