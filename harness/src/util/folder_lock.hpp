// folder_lock.hpp — one writer per results folder: an advisory lock (flock) on FOLDER/.vobench.lock,
// held for the life of the object. A second `vobench run`, `collect` or `report` on the same folder
// refuses at once, naming the process that holds it. The descriptor is close-on-exec, so no cell or
// plugin process inherits (and so keeps) the lock.
#pragma once

#include <filesystem>

namespace vobench {

class FolderLock {
public:
    // Throws std::runtime_error("… is being written by vobench (pid N) …") when another process holds it.
    explicit FolderLock(const std::filesystem::path& folder);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

private:
    int fd_ = -1;
};

}  // namespace vobench
