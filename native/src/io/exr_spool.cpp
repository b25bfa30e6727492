// How passes are appended to an unlinked spool file and read back a band of rows at a time.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/exr_spool.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/names.h"
#include "io/atomic_file.h"
#include "io/exr_file.h"

namespace ss {

namespace {

void writeAll(int fd, const char* data, size_t bytes, uint64_t offset, const std::string& path) {
    while (bytes > 0) {
        ssize_t n = pwrite(fd, data, bytes, off_t(offset));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            fail(SS_ERROR_IO, "cannot write EXR '" + path + "': spooling a pass beside it failed: " +
                                  std::strerror(n < 0 ? errno : ENOSPC));
        data += n;
        bytes -= size_t(n);
        offset += uint64_t(n);
    }
}

void readAll(int fd, char* data, size_t bytes, uint64_t offset, const std::string& path) {
    while (bytes > 0) {
        ssize_t n = pread(fd, data, bytes, off_t(offset));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) fail(SS_ERROR_IO, "cannot write EXR '" + path + "': reading its spool back failed");
        data += n;
        bytes -= size_t(n);
        offset += uint64_t(n);
    }
}

}  // namespace

ExrSpool::ExrSpool(const std::string& path, const std::string& viewLayer) : path_(path), viewLayer_(viewLayer) {
    checkViewLayerName(viewLayer);
    std::filesystem::path target(resolveOutputPath(path));
    std::filesystem::path dir = target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
    // A file without a name (O_TMPFILE), so nothing can be left behind; where the file system
    // lacks that, a named file unlinked at once.
    fd_ = open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd_ < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)) {
        static std::atomic<unsigned> counter{0};
        std::string name = ".ss" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ".spool";
        std::string spool = (dir / name).string();
        fd_ = open(spool.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
        if (fd_ >= 0) unlink(spool.c_str());
    }
    if (fd_ < 0) fail(SS_ERROR_IO, "cannot write EXR '" + path + "': " + std::strerror(errno));
}

ExrSpool::~ExrSpool() {
    if (fd_ >= 0) close(fd_);
}

void ExrSpool::add(const std::string& pass, const Image& image) {
    auto bad = [&](const std::string& what) {
        fail(SS_ERROR_INVALID_ARGUMENT, "cannot write EXR '" + path_ + "': " + what);
    };
    checkPassName(path_, viewLayer_, pass);
    if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * image.height)
        bad("pass " + quoted(pass) + " has no pixels");
    if (passes_.empty()) {
        width_ = image.width;
        height_ = image.height;
    } else if (image.width != width_ || image.height != height_) {
        bad("pass " + quoted(pass) + " is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
            " but the first is " + std::to_string(width_) + "x" + std::to_string(height_));
    }
    if (names_.count(pass)) bad("pass " + quoted(pass) + " appears twice");
    checkExrShape(path_, passes_.size() + 1, width_);
    const size_t bytes = image.pixels.size() * sizeof(float);
    writeAll(fd_, reinterpret_cast<const char*>(image.pixels.data()), bytes, end_, path_);
    passes_.push_back({pass, end_});
    names_.insert(pass);
    end_ += bytes;
}

void ExrSpool::write() {
    if (passes_.empty())
        fail(SS_ERROR_INVALID_ARGUMENT, "cannot write EXR '" + path_ + "': there are no passes to write");
    std::vector<ExrPassRows> rows;
    for (const Spooled& s : passes_) {
        uint64_t offset = s.offset;
        rows.push_back({s.pass, [this, offset](int y0, int count, float* out) {
                            const uint64_t rowBytes = uint64_t(width_) * sizeof(float);
                            readAll(fd_, reinterpret_cast<char*>(out), size_t(rowBytes * uint64_t(count)),
                                    offset + rowBytes * uint64_t(y0), path_);
                        }});
    }
    writeMultilayerExrRows(path_, viewLayer_, width_, height_, rows, methods_, estimates_);
}

void ExrSpool::noteEstimate(const std::string& pass, double rmse) {
    estimates_ += (estimates_.empty() ? "" : ";") + pass + "=" + formatEstimate(rmse);
}

void ExrSpool::noteMethod(const std::string& pass, const std::string& method) {
    methods_ += (methods_.empty() ? "" : ";") + pass + "=" + method;
}

}  // namespace ss
