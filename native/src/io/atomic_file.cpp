// How a file is written to a temporary name, checked, and renamed into place.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace ss {

namespace fs = std::filesystem;

namespace {

// Temporary names live in fixed slots so a signal handler can unlink them without allocating.
constexpr int kSlots = 64;
constexpr size_t kSlotBytes = 4096;
struct TempSlot {
    std::atomic<bool> taken{false};
    std::atomic<bool> ready{false};
    char path[kSlotBytes];
};
std::array<TempSlot, kSlots> tempSlots;

int registerTemp(const std::string& path) {
    if (path.size() + 1 > kSlotBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        bool expected = false;
        if (tempSlots[i].taken.compare_exchange_strong(expected, true)) {
            std::memcpy(tempSlots[i].path, path.c_str(), path.size() + 1);
            tempSlots[i].ready.store(true);
            return i;
        }
    }
    return -1;  // more writes at once than slots: those few are not cleaned up on a signal
}

void releaseTemp(int slot) {
    if (slot < 0) return;
    tempSlots[slot].ready.store(false);
    tempSlots[slot].taken.store(false);
}

std::string kindOf(const fs::file_status& s) {
    switch (s.type()) {
        case fs::file_type::directory: return "a directory";
        case fs::file_type::character: return "a character device";
        case fs::file_type::block: return "a block device";
        case fs::file_type::fifo: return "a FIFO";
        case fs::file_type::socket: return "a socket";
        default: return "not a regular file";
    }
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
    fail(SS_ERROR_IO, "cannot write '" + path + "': " + why +
                          " (outputs are regular files, written through symlinks)");
}

}  // namespace

std::string resolveOutputPath(const std::string& path) {
    if (path.empty()) fail(SS_ERROR_IO, "output path is empty");
    std::error_code ec;
    fs::path target(path);
    fs::file_status link = fs::symlink_status(target, ec);
    if (link.type() == fs::file_type::symlink) {
        target = fs::canonical(target, ec);
        if (ec) refuse(path, "it is a symlink that leads nowhere (" + ec.message() + ")");
    }
    fs::file_status st = fs::status(target, ec);
    if (fs::exists(st) && !fs::is_regular_file(st)) refuse(path, "it is " + kindOf(st));
    if (ec && ec != std::errc::no_such_file_or_directory) refuse(path, ec.message());
    fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    if (!fs::is_directory(dir, ec)) refuse(path, "folder '" + dir.string() + "' does not exist");
    return target.string();
}

StagedFile::StagedFile(const std::string& path, const std::function<void(const std::string&)>& write)
    : path_(path), target_(resolveOutputPath(path)) {
    static std::atomic<unsigned> counter{0};
    // Short, so any name the folder accepts still fits; same folder, so the rename is atomic;
    // a leading dot keeps it out of casual listings.
    fs::path target(target_);
    std::string ext = target.extension().string();
    if (ext.size() > 8) ext.clear();
    std::string name = ".ss" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ".tmp" + ext;
    temp_ = (target.parent_path() / name).string();
    slot_ = registerTemp(temp_);
    try {
        write(temp_);
    } catch (const Error&) {
        std::error_code ignored;
        fs::remove(temp_, ignored);
        releaseTemp(slot_);
        throw;
    } catch (const std::exception& e) {
        std::error_code ignored;
        fs::remove(temp_, ignored);
        releaseTemp(slot_);
        fail(SS_ERROR_IO, "cannot write '" + path + "': " + e.what());
    }
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : path_(std::move(other.path_)), target_(std::move(other.target_)), temp_(std::move(other.temp_)),
      slot_(other.slot_), done_(other.done_) {
    other.done_ = true;
    other.slot_ = -1;
}

StagedFile::~StagedFile() {
    if (done_) return;
    std::error_code ignored;
    fs::remove(temp_, ignored);
    releaseTemp(slot_);
}

void StagedFile::commit() {
    if (done_) return;
    std::error_code ec;
    // The target may have changed while the temporary file was written.
    std::string target = resolveOutputPath(path_);
    fs::file_status old = fs::status(target, ec);
    if (fs::exists(old)) fs::permissions(temp_, old.permissions(), ec);
    fs::rename(temp_, target, ec);
    if (ec) fail(SS_ERROR_IO, "cannot write '" + path_ + "': " + ec.message());
    releaseTemp(slot_);
    done_ = true;
}

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    StagedFile(path, write).commit();
}

void removeTemporaryFiles() noexcept {
    for (TempSlot& s : tempSlots)
        if (s.ready.load()) unlink(s.path);
}

}  // namespace ss
