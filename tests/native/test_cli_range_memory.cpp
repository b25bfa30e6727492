// Whether the reproducers of issue 29 (items 1 and 3) run through the `softshadow` command hold:
// scene files with coordinates far past the camera render the rest of the scene with a warning
// naming the mesh (they aborted in Embree, exit 134), and scene files and resolutions past the
// memory budget are refused before anything is allocated, with the figures.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <chrono>
#include <cmath>
#include <cstring>

#include "cli_run.h"
#include "io/exr_file.h"

namespace {

void writeFile(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// A box over a ground plane under a disk light; `extraMesh` (JSON) is added to the meshes.
std::string sceneJson(const std::string& extraMesh, int side = 32) {
    return R"({"format":"softshadow-scene","version":1,
      "camera":{"look_from":[0,-3,6],"look_at":[0,0,0],"fov_y_degrees":45,"far":100,"width":)" +
           std::to_string(side) + R"(,"height":)" + std::to_string(side) + R"(},
      "lights":[{"name":"Key","type":"disk","position":[1,0,4],"direction":[0,0,-1],"size":0.5}],
      "meshes":[{"name":"Ground","primitive":{"type":"plane","size":6}},
                {"name":"Box","primitive":{"type":"box","size":1},"translate":[0,0,1]})" +
           (extraMesh.empty() ? "" : "," + extraMesh) + "]}";
}

double meanV(const fs::path& exr, const std::string& method) {
    ss::ExrContents c = ss::readMultilayerExr(exr.string());
    const ss::ExrPass* p = c.find("Key_" + method);
    if (!p) return NAN;
    double sum = 0.0;
    for (float v : p->image.pixels) sum += v;
    return sum / double(p->image.pixels.size());
}

// 1. A positions_file holding 1e30, and an inline scene inside the documented 1e15 bound
// (positions 1e15 scaled 1e15), aborted with reference and auto.
TEST(CliRangeMemory, FarCoordinatesInSceneFilesRenderTheRestWithAWarning) {
    fs::path dir = tempDir("i29_05");
    const float xyz[9] = {-2, 2, 0.1f, 1e30f, 2, 0.1f, -2, 2.5f, 0.1f};
    const uint32_t tri[3] = {0, 1, 2};
    std::ofstream(dir / "far.f32", std::ios::binary).write(reinterpret_cast<const char*>(xyz), sizeof xyz);
    std::ofstream(dir / "far.u32", std::ios::binary).write(reinterpret_cast<const char*>(tri), sizeof tri);
    writeFile(dir / "file.json", sceneJson(R"({"name":"FarFile","positions_file":"far.f32","triangles_file":"far.u32"})"));
    writeFile(dir / "inline.json",
              sceneJson(R"({"name":"FarInline","positions":[1e15,0,0, 0,1e15,0, 0,0,1e15],"triangles":[0,1,2],"scale":1e15})"));
    writeFile(dir / "clean.json", sceneJson(""));
    ASSERT_EQ(cli("render " + q(dir / "clean.json") + " -m reference --no-extra -o " + q(dir / "clean.exr")).code, 0);
    const double clean = meanV(dir / "clean.exr", "reference");
    EXPECT_LT(clean, 0.99);
    for (const char* method : {"reference", "auto"})
        for (auto [file, mesh] : {std::pair{"file.json", "FarFile"}, std::pair{"inline.json", "FarInline"}}) {
            fs::path out = dir / (std::string(file) + "." + method + ".exr");
            CliRun r = cli("render " + q(dir / file) + " -m " + method + " --no-extra -o " + q(out));
            ASSERT_EQ(r.code, 0) << method << " " << file << ": " << r.err;
            EXPECT_NE(r.err.find(std::string("warning: mesh '") + mesh + "' skipped"), std::string::npos) << r.err;
            EXPECT_NE(r.err.find("beyond the scene range"), std::string::npos) << r.err;
            EXPECT_NEAR(meanV(out, method), clean, 0.03) << method << " " << file;
        }
    fs::remove_all(dir);
}

// 3. A 7 KB scene file (100 boxes of 2048 subdivisions) grew to tens of GB; a resolution past
// the memory budget rendered until the kernel stepped in.
TEST(CliRangeMemory, ScenesAndResolutionsPastTheBudgetAreRefusedUpFront) {
    fs::path dir = tempDir("i29_06");
    std::string boxes;
    for (int i = 0; i < 100; ++i)
        boxes += std::string(i ? "," : "") + R"({"name":"B)" + std::to_string(i) +
                 R"(","primitive":{"type":"box","subdivisions":2048}})";
    writeFile(dir / "boxes.json", sceneJson(boxes));
    const auto t0 = std::chrono::steady_clock::now();
    expectFailure(cli("report " + q(dir / "boxes.json")),
                  {"boxes.json", "meshes[2]", "50331662 triangles", "budget of 16777216", "bytes a triangle"});
    // Refused from the parameters: nothing was built (a box of 2048 subdivisions takes seconds).
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
    writeFile(dir / "s.json", sceneJson(""));
    expectFailure(cli("render " + q(dir / "s.json") + " -m shadow_map --width 8192 --height 8192 --set memory_limit_mb=2000 -o " +
                      q(dir / "o.exr")),
                  {"Key", "shadow_map at 8192 x 8192 needs about", "GB", "memory limit 2.10 GB"});
    EXPECT_FALSE(fs::exists(dir / "o.exr"));
    fs::remove_all(dir);
}

}  // namespace
