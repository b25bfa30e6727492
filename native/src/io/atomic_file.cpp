// How a file is written to a temporary name, checked, and renamed into place.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/atomic_file.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
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

// Eight hex digits naming this host and pid namespace in temporary names, so a sweep judges
// only the files of processes whose pids it can see: a shared folder also holds other
// machines' and containers' writes in progress.
const std::string& processSpaceTag() {
    static const std::string tag = [] {
        char host[256] = {};
        gethostname(host, sizeof host - 1);
        std::error_code ec;
        std::string space = std::string(host) + "|" + fs::read_symlink("/proc/self/ns/pid", ec).string();
        uint32_t h = 2166136261u;
        for (unsigned char c : space) h = (h ^ c) * 16777619u;
        char out[9];
        std::snprintf(out, sizeof out, "%08x", h);
        return std::string(out);
    }();
    return tag;
}

// A temporary name's parts: ".ss<pid>-<tag>_<n>.tmp..." (or, from earlier versions,
// ".ss<pid>_<n>.tmp..." without a tag). False for any other name.
bool parseTemporaryName(const std::string& name, long* pid, std::string* tag) {
    if (name.rfind(".ss", 0) != 0) return false;
    size_t at = 3, digits = name.find_first_not_of("0123456789", at);
    if (digits == std::string::npos || digits == at || digits - at > 9) return false;
    *pid = std::stol(name.substr(at, digits - at));
    at = digits;
    tag->clear();
    if (name[at] == '-') {
        *tag = name.substr(at + 1, 8);
        at += 9;
    }
    if (at >= name.size() || name[at] != '_') return false;
    size_t end = name.find_first_not_of("0123456789", at + 1);
    return end != std::string::npos && end > at + 1 && name.compare(end, 4, ".tmp") == 0;
}

// Removes the temporary files in `folder` that a process killed mid-write left (SIGKILL, a
// crash): its pid is gone from this host's pid namespace. Files without a tag are older
// versions', judged by the pid only once they are an hour old.
void sweepStaleTemporaryFiles(const fs::path& folder) {
    std::error_code ec;
    for (fs::directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        long pid = 0;
        std::string tag;
        if (!parseTemporaryName(name, &pid, &tag) || pid <= 0 || pid == long(getpid())) continue;
        if (!tag.empty() && tag != processSpaceTag()) continue;
        if (kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
        std::error_code timeError;
        if (tag.empty() &&
            fs::last_write_time(it->path(), timeError) > fs::file_time_type::clock::now() - std::chrono::hours(1))
            continue;
        if (!timeError) {
            std::error_code ignored;
            fs::remove(it->path(), ignored);
        }
    }
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
    std::string name = ".ss" + std::to_string(getpid()) + "-" + processSpaceTag() + "_" +
                       std::to_string(counter++) + ".tmp" + ext;
    fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    sweepStaleTemporaryFiles(folder);
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

namespace {

extern "C" void removeTemporaryFilesAndEnd(int sig) {
    removeTemporaryFiles();
    signal(sig, SIG_DFL);
    raise(sig);
}

}  // namespace

int removeTemporaryFilesOnSignals() noexcept {
    int installed = 0;
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction current {};
        if (sigaction(sig, nullptr, &current) != 0) continue;
        if (current.sa_handler == removeTemporaryFilesAndEnd) {
            ++installed;
            continue;
        }
        if ((current.sa_flags & SA_SIGINFO) || current.sa_handler != SIG_DFL) continue;
        struct sigaction ours {};
        ours.sa_handler = removeTemporaryFilesAndEnd;
        sigemptyset(&ours.sa_mask);
        if (sigaction(sig, &ours, nullptr) == 0) ++installed;
    }
    return installed;
}

}  // namespace ss
