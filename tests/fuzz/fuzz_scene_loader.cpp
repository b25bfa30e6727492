// Whether any byte string given to the scene loader ends in a scene or an ss::Error, never a
// crash, a hang, an unbounded allocation or another exception (libFuzzer target).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/scene_file.h"

namespace {

// A folder with one small external mesh, so inputs that name "p.f32"/"t.u32" reach that code.
std::string meshFolder() {
    static const std::string dir = [] {
        std::filesystem::path d = std::filesystem::temp_directory_path() / ("ss_fuzz_scene_" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        const uint32_t tri[3] = {0, 1, 2};
        std::ofstream(d / "p.f32", std::ios::binary).write(reinterpret_cast<const char*>(xyz), sizeof xyz);
        std::ofstream(d / "t.u32", std::ios::binary).write(reinterpret_cast<const char*>(tri), sizeof tri);
        return d.string();
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string text(reinterpret_cast<const char*>(data), size);
    try {
        // The budget's check is the same code at any limit; at the users' 2^24 triangles an input
        // the loader rightly accepts takes longer than the 10 s libFuzzer allows an input.
        constexpr int64_t kFuzzGeometry = int64_t(1) << 16;
        ss::Scene scene = ss::parseSceneText(text, meshFolder(), "fuzz.json", kFuzzGeometry);
        (void)scene;
    } catch (const ss::Error& e) {
        if (e.status() == SS_ERROR_INTERNAL) std::abort();  // every refusal names the input
    }
    return 0;
}
