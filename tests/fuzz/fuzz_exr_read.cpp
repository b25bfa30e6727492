// Whether any byte string read as an EXR, as `softshadow compare` reads one, ends in its passes
// or an ss::Error, never a crash, a huge allocation or another exception (libFuzzer target).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/exr_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path =
        (std::filesystem::temp_directory_path() / ("ss_fuzz_exr_" + std::to_string(getpid()) + ".exr")).string();
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    try {
        ss::ExrContents contents = ss::readMultilayerExr(path);
        (void)contents;
    } catch (const ss::Error& e) {
        if (e.status() != SS_ERROR_IO) std::abort();
    }
    return 0;
}
