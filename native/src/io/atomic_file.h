// How an output file is written under a temporary name in its folder and renamed into place,
// so no reader ever sees a half-written file and a failure leaves the old file as it was.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <string>

namespace ss {

// Where a write to `path` lands: `path` itself, or the file a symlink chain ends at (outputs are
// written through symlinks). Throws ss::Error(SS_ERROR_IO) naming `path` when it is, or leads to,
// anything but a regular file or a new name in an existing folder (devices, FIFOs, sockets,
// folders, dangling or looping symlinks, a missing folder).
std::string resolveOutputPath(const std::string& path);

// A file written to a temporary name beside its target and not yet renamed into place. The
// destructor removes the temporary file unless commit() ran, so every failure before the
// commit leaves the old target untouched; several staged files commit together.
class StagedFile {
public:
    // Calls write(tempPath) with a short fresh name in the target's folder (keeping a short
    // extension, for writers that pick a format by it). When write throws, the temporary file
    // is removed and ss::Error(SS_ERROR_IO) names `path` (write's own ss::Error passes through).
    // First removes the folder's temporary files whose writer was killed (their pid is gone).
    StagedFile(const std::string& path, const std::function<void(const std::string&)>& write);
    ~StagedFile();
    StagedFile(StagedFile&& other) noexcept;
    StagedFile& operator=(StagedFile&&) = delete;
    StagedFile(const StagedFile&) = delete;
    StagedFile& operator=(const StagedFile&) = delete;

    // Renames the temporary file over the target (checked again first), keeping the old
    // file's permission bits. Throws ss::Error(SS_ERROR_IO) naming the path.
    void commit();
    const std::string& path() const { return path_; }

private:
    std::string path_, target_, temp_;
    int slot_ = -1;  // in the registry removeTemporaryFiles() empties
    bool done_ = false;
};

// StagedFile(path, write).commit().
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Unlinks every temporary file a write in progress has made. Async-signal-safe: for a host's
// SIGINT/SIGTERM handler, so an interrupted write leaves nothing behind.
void removeTemporaryFiles() noexcept;

// For SIGINT, SIGTERM and SIGHUP where each still has its default action (it ends the process):
// a handler that calls removeTemporaryFiles() and then ends the process by the signal. A signal
// the host handles or ignores keeps its disposition. Returns how many handlers it installed.
int removeTemporaryFilesOnSignals() noexcept;

}  // namespace ss
