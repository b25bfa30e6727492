// Whether the `softshadow` command fails with one clear line and no output file on bad input,
// and renders, compares and reports as documented.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "io/exr_file.h"

namespace {

namespace fs = std::filesystem;

const char* kTetMesh = R"({"name":"Tet","positions":%P%,"triangles":%T%})";

std::string scene(const std::string& positions, const std::string& triangles, const std::string& size = "0.5") {
    std::string mesh = kTetMesh;
    mesh.replace(mesh.find("%P%"), 3, positions);
    mesh.replace(mesh.find("%T%"), 3, triangles);
    return R"({"format":"softshadow-scene","version":1,
      "camera":{"look_from":[3,-3,3],"look_at":[0,0,0],"fov_y_degrees":40,"width":32,"height":24},
      "lights":[{"name":"Key","type":"disk","position":[0,0,4],"direction":[0,0,-1],"size":)" + size + R"(}],
      "meshes":[)" + mesh + "]}";
}
const std::string kPos = "[0,0,0, 1,0,0, 0,1,0, 0,0,1]";
const std::string kTri = "[0,2,1, 0,1,3, 1,2,3, 0,3,2]";

TEST(Cli, BadInputFailsWithOneLineAndNoOutput) {
    fs::path dir = tempDir("bad");
    std::ofstream(dir / "malformed.json") << "{\"format\": \"softshadow-scene\",";
    std::ofstream(dir / "nan.json") << scene("[0,0,0, 1,0,0, 0,\"NaN\",0, 0,0,1]", kTri);
    std::ofstream(dir / "index.json") << scene(kPos, "[0,2,1, 0,1,3, 1,2,3, 0,3,12]");
    std::ofstream(dir / "zero.json") << scene(kPos, kTri, "0");
    std::ofstream(dir / "good.json") << scene(kPos, kTri);
    size_t before = entries(dir);
    std::string out = " -m reference -o '" + (dir / "out.exr").string() + "'";
    auto render = [&](const std::string& file) { return cli("render '" + (dir / file).string() + "'" + out); };

    expectFailure(render("missing.json"), {"missing.json", "does not exist"});
    expectFailure(render("malformed.json"), {"malformed.json", "malformed JSON"});
    expectFailure(render("nan.json"), {"nan.json", "meshes[0].positions[7]", "expected a number"});
    expectFailure(render("index.json"), {"meshes[0].triangles[11]", "vertex index 12"});
    expectFailure(render("zero.json"), {"lights[0]", "size greater than zero"});
    expectFailure(cli("render '" + (dir / "good.json").string() + "' -m reference -o '" +
                      (dir / "no_folder" / "out.exr").string() + "'"),
                  {"no_folder", "does not exist"});
    expectFailure(cli("render '" + (dir / "good.json").string() + "' -m reference -o '" + dir.string() + "'"),
                  {"is a directory"});
    expectFailure(cli("render '" + (dir / "good.json").string() + "' -m nonsense" + out), {"nonsense"});
    expectFailure(cli("render '" + (dir / "good.json").string() + "' -m reference -l Nobody" + out),
                  {"no light named 'Nobody'", "Key"});
    expectFailure(cli("render '" + (dir / "good.json").string() + "' -o x.exr"), {"needs a method"});
    expectFailure(cli("frobnicate"), {"unknown command 'frobnicate'"});
    expectFailure(cli("compare '" + (dir / "a.exr").string() + "' '" + (dir / "b.exr").string() + "'"), {"a.exr"});
    EXPECT_EQ(entries(dir), before);  // nothing written, nothing half-written
    fs::remove_all(dir);
}

TEST(Cli, ReportListsMeshes) {
    CliRun r = cli("report '" SS_SOURCE_DIR "/examples/scenes/demo.json' --json");
    ASSERT_EQ(r.code, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    ASSERT_GE(j["meshes"].size(), 2u);
    EXPECT_EQ(j["meshes"][0]["mesh"], "Ground");
    EXPECT_EQ(j["meshes"][0]["closed_manifold"], false);  // a plane is open
    EXPECT_EQ(j["meshes"][1]["closed_manifold"], true);
    EXPECT_EQ(j["lights"][0]["name"], "Area");
    EXPECT_EQ(j["camera"]["width"], 640);
    CliRun table = cli("report '" SS_SOURCE_DIR "/examples/scenes/demo.json'");
    EXPECT_EQ(table.code, 0);
    EXPECT_NE(table.out.find("Torus"), std::string::npos) << table.out;
}

// Each light's shadow linking (blockers) and light linking (receivers) by mesh name: every
// mesh when the light has no list, "none" for an empty one.
TEST(Cli, ReportListsEachLightsLinks) {
    fs::path dir = tempDir("report_links");
    std::ofstream(dir / "links.json") << R"({"format":"softshadow-scene","version":1,
      "camera":{"look_from":[3,-3,3],"look_at":[0,0,0],"fov_y_degrees":40,"width":32,"height":24},
      "lights":[{"name":"Key","type":"disk","position":[0,0,4],"direction":[0,0,-1],"size":1,
                 "blockers":["Tree"],"receivers":[0,"Tree"]},
                {"name":"Fill","type":"point","position":[1,0,4],"direction":[0,0,-1],"blockers":[]},
                {"name":"Rim","type":"point","position":[-1,0,4],"direction":[0,0,-1]}],
      "meshes":[{"name":"Ground","primitive":{"type":"plane","size":4}},
                {"name":"Rock","primitive":{"type":"box","size":1},"translate":[1,0,1]},
                {"name":"Tree","primitive":{"type":"box","size":1},"translate":[-1,0,1]}]})";
    CliRun r = cli("report '" + (dir / "links.json").string() + "' --json");
    ASSERT_EQ(r.code, 0) << r.err;
    auto lights = nlohmann::json::parse(r.out)["lights"];
    ASSERT_EQ(lights.size(), 3u);
    EXPECT_EQ(lights[0]["blockers"], nlohmann::json::array({"Tree"}));
    EXPECT_EQ(lights[0]["receivers"], nlohmann::json::array({"Ground", "Tree"}));
    EXPECT_EQ(lights[1]["blockers"], nlohmann::json::array());
    EXPECT_TRUE(lights[1]["receivers"].is_null());
    EXPECT_TRUE(lights[2]["blockers"].is_null());
    EXPECT_TRUE(lights[2]["receivers"].is_null());
    CliRun table = cli("report '" + (dir / "links.json").string() + "'");
    ASSERT_EQ(table.code, 0) << table.err;
    for (const char* line : {"shadowed by (blockers): Tree\n", "lights (receivers): Ground, Tree\n",
                             "shadowed by (blockers): none\n", "lights (receivers): every mesh\n"})
        EXPECT_NE(table.out.find(line), std::string::npos) << line << " in\n" << table.out;
    fs::remove_all(dir);
}

TEST(Cli, CompareGivesKnownNumbers) {
    fs::path dir = tempDir("compare");
    // A: V = 0 on the left half, 1 on the right; B: 0.5 everywhere; a mask of the top row only.
    ss::Image a(8, 2, 1.0f), b(8, 2, 0.5f), mask(8, 2, 0.0f);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) a.at(x, y) = 0.0f;
    for (int x = 0; x < 8; ++x) mask.at(x, 0) = 1.0f;
    ss::writeMultilayerExr((dir / "a.exr").string(), "ViewLayer", {{"L_reference", &a}, {"L_reference_mask", &mask}});
    ss::writeMultilayerExr((dir / "b.exr").string(), "ViewLayer", {{"L_shadow_map", &b}});
    CliRun r = cli("compare '" + (dir / "a.exr").string() + "' '" + (dir / "b.exr").string() + "' --json");
    ASSERT_EQ(r.code, 0) << r.err;
    auto rows = nlohmann::json::parse(r.out);
    ASSERT_EQ(rows.size(), 1u);
    // Different method names pair by light and layer; |a - b| = 0.5 on the 8 masked pixels.
    EXPECT_EQ(rows[0]["a"], "L_reference");
    EXPECT_EQ(rows[0]["b"], "L_shadow_map");
    EXPECT_EQ(rows[0]["pixels"], 8);
    EXPECT_DOUBLE_EQ(rows[0]["rmse"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(rows[0]["p99"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(rows[0]["umbra_iou"].get<double>(), 0.0);
    CliRun all = cli("compare '" + (dir / "a.exr").string() + "' '" + (dir / "b.exr").string() + "' --mask none --json");
    EXPECT_EQ(nlohmann::json::parse(all.out)[0]["pixels"], 16);
    CliRun table = cli("compare '" + (dir / "a.exr").string() + "' '" + (dir / "b.exr").string() + "'");
    EXPECT_EQ(table.code, 0);
    EXPECT_NE(table.out.find("L_reference vs L_shadow_map"), std::string::npos) << table.out;
    fs::remove_all(dir);
}

TEST(Cli, RenderWritesExactPassNames) {
    fs::path dir = tempDir("render");
    std::string out = (dir / "demo.exr").string();
    CliRun r = cli("render '" SS_SOURCE_DIR "/examples/scenes/demo.json' -m reference --width 40 --samples 4 -o '" +
                out + "' --png-dir '" + (dir / "png").string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("wrote"), std::string::npos) << r.out;
    ss::ExrContents back = ss::readMultilayerExr(out);
    EXPECT_EQ(back.width, 40);
    EXPECT_EQ(back.height, 30);  // --width alone keeps the 4:3 aspect
    ASSERT_TRUE(back.find("Area_reference"));
    EXPECT_EQ(back.find("Area_reference")->layer, "ViewLayer");
    EXPECT_TRUE(fs::exists(dir / "png" / "Area_reference.png"));
    // The same file against itself: zero error on every shared pass.
    CliRun c = cli("compare '" + out + "' '" + out + "' --json");
    ASSERT_EQ(c.code, 0) << c.err;
    for (auto& row : nlohmann::json::parse(c.out)) EXPECT_EQ(row["rmse"].get<double>(), 0.0);
    fs::remove_all(dir);
}

TEST(Cli, AdaptiveReferenceAndRefinedPcssWriteTheirRayCounts) {
    fs::path dir = tempDir("adaptive");
    std::string out = (dir / "demo.exr").string();
    CliRun r = cli("render '" SS_SOURCE_DIR
                   "/examples/scenes/demo.json' -m reference,pcss --width 64 "
                   "-l Area --refine --set adaptive=on --set error_target=0.02 -o '" +
                   out + "'");
    // adaptive is a reference key only: pcss refuses it by name.
    expectFailure(r, {"method 'pcss' has no setting 'adaptive'"});
    r = cli("render '" SS_SOURCE_DIR "/examples/scenes/demo.json' -m pcss --width 64 --refine -o '" + out +
            "'");
    ASSERT_EQ(r.code, 0) << r.err;
    ss::ExrContents back = ss::readMultilayerExr(out);
    ASSERT_TRUE(back.find("Area_pcss_rays"));
    ASSERT_TRUE(back.find("Area_pcss_refined"));
    // Refinement is --refine, not a setting.
    expectFailure(
        cli("render '" SS_SOURCE_DIR "/examples/scenes/demo.json' -m pcss --width 64 --set refine=on -o '" +
            out + "'"),
        {"method 'pcss' has no setting 'refine'"});
    r = cli("render '" SS_SOURCE_DIR "/examples/scenes/demo.json' -m reference --width 64 --set adaptive=on -o '" +
            out + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    back = ss::readMultilayerExr(out);
    ASSERT_TRUE(back.find("Area_reference_rays"));
    fs::remove_all(dir);
}

// The sweep's paper fill is one --set away; a misspelt fill value fails naming the choices.
TEST(Cli, SweepRingFillRendersAndABadFillFails) {
    fs::path dir = tempDir("sweep_rings");
    std::string out = (dir / "demo.exr").string();
    CliRun r = cli("render '" SS_SOURCE_DIR "/examples/scenes/demo.json' -m sweep --width 48 --set fill=rings -o '" +
                   out + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    ss::ExrContents back = ss::readMultilayerExr(out);
    const auto* pass = back.find("Area_sweep");
    ASSERT_TRUE(pass);
    float lo = 1.0f;
    for (float v : pass->image.pixels) lo = std::min(lo, v);
    EXPECT_LT(lo, 0.5f);  // a shadow was drawn
    fs::remove(out);
    expectFailure(cli("render '" SS_SOURCE_DIR "/examples/scenes/demo.json' -m sweep --width 48 --set fill=ring -o '" +
                      out + "'"),
                  {"setting 'fill' = 'ring' is not one of: smooth, steps, rings"});
    EXPECT_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

TEST(Cli, UnknownSettingKeyFailsNamingItAndTheKnownKeys) {
    // A typo (blocker_sample for blocker_samples) must not render the default with exit 0.
    fs::path dir = tempDir("setting_typo");
    std::ofstream(dir / "good.json") << scene(kPos, kTri);
    fs::path out = dir / "out.exr";
    expectFailure(cli("render '" + (dir / "good.json").string() + "' -m pcss --set blocker_sample=64 -o '" +
                      out.string() + "'"),
                  {"no setting 'blocker_sample'", "blocker_samples, pcf_samples, shadow_map_size, max_search"});
    EXPECT_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

TEST(Cli, OcclusionTexturesSlicingRunsFromTheCommandLine) {
    // Figure 4's comparison is a user setting: slicing=orthographic renders (and differs from the
    // default perspective slicing); an unknown value fails naming both, writing nothing.
    fs::path dir = tempDir("slicing");
    std::string scene = "render '" SS_SOURCE_DIR "/examples/scenes/demo.json' -m occlusion_textures --width 64 ";
    std::string perspective = (dir / "perspective.exr").string(), orthographic = (dir / "orthographic.exr").string();
    CliRun r = cli(scene + "-o '" + perspective + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    r = cli(scene + "--set slicing=orthographic -o '" + orthographic + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    ss::ExrContents p = ss::readMultilayerExr(perspective), o = ss::readMultilayerExr(orthographic);
    ASSERT_TRUE(p.find("Area_occlusion_textures") && o.find("Area_occlusion_textures"));
    EXPECT_NE(p.find("Area_occlusion_textures")->image.pixels, o.find("Area_occlusion_textures")->image.pixels);
    fs::path bad = dir / "bad.exr";
    expectFailure(cli(scene + "--set slicing=fisheye -o '" + bad.string() + "'"),
                  {"slicing", "fisheye", "perspective, orthographic"});
    EXPECT_FALSE(fs::exists(bad));
    fs::remove_all(dir);
}

}  // namespace
