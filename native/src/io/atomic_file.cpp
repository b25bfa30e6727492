// How a file is written to a temporary name and renamed into place.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace ss {

namespace fs = std::filesystem;

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    if (path.empty()) fail(SS_ERROR_IO, "output path is empty");
    fs::path target(path);
    std::error_code ec;
    if (fs::is_directory(target, ec))
        fail(SS_ERROR_IO, "cannot write '" + path + "': it is a directory");
    static std::atomic<unsigned> counter{0};
    // Same folder, so the rename is atomic; same extension, so writers that pick a format by
    // extension still work; a leading dot keeps it out of casual listings.
    std::string tempName(1, '.');
    tempName += target.stem().string();
    tempName += ".tmp" + std::to_string(getpid()) + "_" + std::to_string(counter++);
    tempName += target.extension().string();
    fs::path temp = target.parent_path() / tempName;
    auto removeTemp = [&] {
        std::error_code ignored;
        fs::remove(temp, ignored);
    };
    try {
        write(temp.string());
    } catch (const Error&) {
        removeTemp();
        throw;
    } catch (const std::exception& e) {
        removeTemp();
        fail(SS_ERROR_IO, "cannot write '" + path + "': " + e.what());
    }
    fs::rename(temp, target, ec);
    if (ec) {
        removeTemp();
        fail(SS_ERROR_IO, "cannot write '" + path + "': " + ec.message());
    }
}

}  // namespace ss
