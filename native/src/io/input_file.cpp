// How an input file is opened without blocking, checked with fstat and read to its stated size.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "core/error.h"

namespace ss {

namespace {

std::string whyNotOpened(int err) {
    switch (err) {
        case ENOENT: return "does not exist";
        case ENOTDIR: return "does not exist (a part of the path is not a folder)";
        case ENAMETOOLONG: return "cannot be opened: the path is too long";
        case ELOOP: return "cannot be opened: its symlinks form a loop";
        case EACCES: return "cannot be opened: permission denied";
        default: return std::string("cannot be opened: ") + std::strerror(err);
    }
}

const char* kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

struct Fd {
    int fd = -1;
    ~Fd() {
        if (fd >= 0) close(fd);
    }
};

// Opens without blocking (so a FIFO cannot hang the open) and refuses anything but a regular file.
Fd openRegular(const std::string& path, const std::string& what, struct stat& st) {
    auto bad = [&](const std::string& problem) { fail(SS_ERROR_IO, what + " '" + path + "' " + problem); };
    if (path.empty()) fail(SS_ERROR_IO, what + ": the path is empty");
    Fd f{open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (f.fd < 0) bad(whyNotOpened(errno));
    if (fstat(f.fd, &st) != 0) bad(std::string("cannot be read: ") + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) bad(std::string("is ") + kindOf(st.st_mode) + " (allowed: a regular file)");
    return Fd{std::exchange(f.fd, -1)};
}

}  // namespace

uint64_t checkInputFile(const std::string& path, const std::string& what) {
    struct stat st {};
    Fd f = openRegular(path, what, st);
    return uint64_t(st.st_size);
}

std::string readInputFile(const std::string& path, const std::string& what, uint64_t maxBytes) {
    auto bad = [&](const std::string& problem) { fail(SS_ERROR_IO, what + " '" + path + "' " + problem); };
    struct stat st {};
    Fd f = openRegular(path, what, st);
    if (uint64_t(st.st_size) > maxBytes)
        bad("is " + std::to_string(uint64_t(st.st_size)) + " bytes (the limit is " + std::to_string(maxBytes) +
            " bytes)");
    std::string bytes(size_t(st.st_size), '\0');
    size_t done = 0;
    while (done < bytes.size()) {
        ssize_t n = read(f.fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) bad(std::string("cannot be read: ") + std::strerror(errno));
        if (n == 0) break;  // shrank while being read
        done += size_t(n);
    }
    bytes.resize(done);
    return bytes;
}

}  // namespace ss
