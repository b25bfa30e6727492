// Whether bad input and limits (docs/reliability.md) run through the `softshadow` command get a
// clear error naming the input and what is allowed, and leave every existing file as it was. One
// test per class of bad input.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>

#include <chrono>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "io/exr_file.h"

extern char** environ;

namespace {

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeFile(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// A scene with one disk light named `light` (JSON-escaped by the caller) over a tetrahedron.
std::string sceneJson(const std::string& lightsJson, int w = 32, int h = 24) {
    return R"({"format":"softshadow-scene","version":1,
      "camera":{"look_from":[3,-3,3],"look_at":[0,0,0],"fov_y_degrees":40,"width":)" + std::to_string(w) +
           R"(,"height":)" + std::to_string(h) + R"(},
      "lights":[)" + lightsJson + R"(],
      "meshes":[{"name":"Tet","positions":[0,0,0, 1,0,0, 0,1,0, 0,0,1],"triangles":[0,2,1, 0,1,3, 1,2,3, 0,3,2]},
                {"name":"Ground","primitive":{"type":"plane","size":6}}]})";
}
std::string disk(const std::string& name, const std::string& extra = "") {
    return R"({"name":)" + nlohmann::json(name).dump() + R"(,"type":"disk","position":[0,0,4],"direction":[0,0,-1],"size":0.5)" +
           extra + "}";
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// 1. The output path is replaced whatever it is.
TEST(CliReliability, OutputMustBeARegularFileSymlinksWrittenThrough) {
    fs::path dir = tempDir("i14_01");
    writeFile(dir / "s.json", sceneJson(disk("Key")));
    std::string render = "render " + q(dir / "s.json") + " -m shadow_map -o ";
    expectFailure(cli(render + "/dev/null"), {"/dev/null", "character device", "regular files"});
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    ASSERT_EQ(mkfifo((dir / "fifo.exr").c_str(), 0644), 0);
    expectFailure(cli(render + q(dir / "fifo.exr")), {"fifo.exr", "FIFO"});
    EXPECT_TRUE(fs::is_fifo(dir / "fifo.exr"));
    expectFailure(cli(render + q(dir)), {"is a directory"});
    fs::create_symlink(dir / "nowhere" / "x.exr", dir / "dangling.exr");
    expectFailure(cli(render + q(dir / "dangling.exr")), {"dangling.exr", "symlink that leads nowhere"});
    // A symlink is written through: the link stays a link, its target gets the EXR.
    writeFile(dir / "target.exr", "old");
    fs::create_symlink("target.exr", dir / "link.exr");
    CliRun ok = cli(render + q(dir / "link.exr"));
    ASSERT_EQ(ok.code, 0) << ok.err;
    EXPECT_TRUE(fs::is_symlink(dir / "link.exr"));
    EXPECT_EQ(ss::readMultilayerExr((dir / "target.exr").string()).passes.size(), 5u);  // V mask umbra penumbra + debug
    fs::remove_all(dir);
}

// 2. A failed --png-dir deletes the previous EXR.
TEST(CliReliability, FailedPreviewFolderKeepsTheOldExr) {
    fs::path dir = tempDir("i14_02");
    writeFile(dir / "s.json", sceneJson(disk("Key")));
    writeFile(dir / "out.exr", "old\n");
    writeFile(dir / "afile", "x\n");
    size_t before = entries(dir);
    CliRun r = cli("render " + q(dir / "s.json") + " -m shadow_map -o " + q(dir / "out.exr") + " --png-dir " + q(dir / "afile"));
    expectFailure(r, {"afile", "not a folder"});
    EXPECT_EQ(readFile(dir / "out.exr"), "old\n");
    EXPECT_EQ(readFile(dir / "afile"), "x\n");
    EXPECT_EQ(entries(dir), before);
    // A render that fails after earlier results' previews were staged keeps the old EXR and
    // the old previews (penumbra_map refuses a sun, after shadow_map rendered it).
    fs::create_directories(dir / "png");
    writeFile(dir / "png" / "Sun_shadow_map.png", "old sun preview");
    writeFile(dir / "sun.json", sceneJson(R"({"name":"Sun","type":"sun","direction":[0.2,0,-1],"angle":0.05})"));
    expectFailure(cli("render " + q(dir / "sun.json") + " -m shadow_map,penumbra_map -o " + q(dir / "out.exr") +
                      " --png-dir " + q(dir / "png")),
                  {"penumbra_map", "Sun", "sun"});
    EXPECT_EQ(readFile(dir / "out.exr"), "old\n");
    EXPECT_EQ(readFile(dir / "png" / "Sun_shadow_map.png"), "old sun preview");
    EXPECT_EQ(entries(dir / "png"), 1u);  // no staged preview left behind
    EXPECT_EQ(entries(dir), before + 2);  // sun.json and png/
    fs::remove(dir / "png" / "Sun_shadow_map.png");
    // An EXR that cannot be written keeps the old previews too.
    CliRun first = cli("render " + q(dir / "s.json") + " -m shadow_map -o " + q(dir / "out.exr") + " --png-dir " + q(dir / "png"));
    ASSERT_EQ(first.code, 0) << first.err;
    std::string preview = readFile(dir / "png" / "Key_shadow_map.png");
    writeFile(dir / "png" / "Key_shadow_map.png", "old preview");
    fs::remove(dir / "out.exr");
    fs::create_symlink(dir / "no_folder" / "x.exr", dir / "out.exr");
    size_t pngs = entries(dir / "png");
    expectFailure(cli("render " + q(dir / "s.json") + " -m shadow_map -o " + q(dir / "out.exr") + " --png-dir " + q(dir / "png")),
                  {"out.exr"});
    EXPECT_EQ(readFile(dir / "png" / "Key_shadow_map.png"), "old preview");
    EXPECT_EQ(entries(dir / "png"), pngs);
    fs::remove_all(dir);
}

// 3. Light names escape the PNG folder.
TEST(CliReliability, LightNamesStayInsideThePreviewFolder) {
    fs::path dir = tempDir("i14_03");
    fs::path outside = dir / "somewhere";
    fs::create_directories(outside);
    writeFile(dir / "s.json", sceneJson(disk(outside.string() + "/escaped") + "," + disk("../up") + "," + disk("a/b\\c")));
    CliRun r = cli("render " + q(dir / "s.json") + " -m shadow_map --no-extra -o " + q(dir / "out.exr") + " --png-dir " +
                   q(dir / "o" / "png"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(entries(outside), 0u);  // nothing written where the name points
    EXPECT_EQ(entries(dir / "o"), 1u);  // only the preview folder
    for (const auto& e : fs::recursive_directory_iterator(dir / "o" / "png")) {
        EXPECT_TRUE(e.is_regular_file()) << e.path();  // no subfolders
        EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
    }
    EXPECT_TRUE(fs::exists(dir / "o" / "png" / "___up_shadow_map.png"));
    EXPECT_TRUE(fs::exists(dir / "o" / "png" / "a_b_c_shadow_map.png"));
    EXPECT_EQ(entries(dir / "o" / "png"), 6u);  // 3 lights x (V, mask)
    fs::remove_all(dir);
}

// 5. Geometry files and the scene path are read without limits (CLI side: the scene path).
TEST(CliReliability, ScenePathMustBeABoundedRegularFile) {
    fs::path dir = tempDir("i14_05");
    std::string tail = " -m shadow_map -o " + q(dir / "out.exr");
    expectFailure(cli("render /dev/zero" + tail), {"/dev/zero", "character device", "allowed: a regular file"});
    ASSERT_EQ(mkfifo((dir / "fifo.json").c_str(), 0644), 0);
    auto t0 = std::chrono::steady_clock::now();
    expectFailure(cli("render " + q(dir / "fifo.json") + tail), {"fifo.json", "FIFO"});
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(20));  // no hang
    expectFailure(cli("render " + q(dir) + tail), {"a folder"});
    // Over the scene-file limit (256 MiB), refused from its size before it is read.
    {
        std::ofstream big(dir / "big.json", std::ios::binary);
        big.seekp((256 << 20) + 1);
        big.put(' ');
    }
    expectFailure(cli("render " + q(dir / "big.json") + tail), {"big.json", "the limit is 268435456 bytes"});
    EXPECT_EQ(entries(dir), 2u);  // the FIFO and big.json: no output
    fs::remove_all(dir);
}

// 6. compare trusts the EXR header.
TEST(CliReliability, CompareRefusesAHeaderLargerThanItsFile) {
    fs::path dir = tempDir("i14_06");
    ss::Image v(16, 16, 0.5f);
    ss::writeMultilayerExr((dir / "a.exr").string(), "ViewLayer", {{"L_reference", &v}, {"L_shadow_map", &v}});
    std::string bytes = readFile(dir / "a.exr");
    // dataWindow: "dataWindow\0box2i\0" + int32 size 16 + xMin yMin xMax yMax.
    std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
    size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    int32_t box[4] = {0, 0, 29999, 29999};
    bytes.replace(at + key.size() + 4, 16, reinterpret_cast<const char*>(box), 16);
    writeFile(dir / "huge.exr", bytes);
    expectFailure(cli("compare " + q(dir / "huge.exr")), {"huge.exr", "30000x30000", "at most 67108864"});
    int32_t tall[4] = {0, 0, 7999, 7999};  // within the pixel limit, but not in a 1 KB file
    bytes.replace(at + key.size() + 4, 16, reinterpret_cast<const char*>(tall), 16);
    writeFile(dir / "tall.exr", bytes);
    expectFailure(cli("compare " + q(dir / "tall.exr")), {"tall.exr", "8000x8000", "more than its"});
    expectFailure(cli("compare /dev/zero"), {"/dev/zero", "character device"});
    // Found by fuzz_exr_read: a 349-byte file whose "Software" attribute declares 1.9 GB.
    expectFailure(cli("compare '" SS_SOURCE_DIR "/tests/fuzz/corpus/exr/huge_string_attribute.exr'"),
                  {"huge_string_attribute.exr", "attribute 'Software' declares 1979711504 bytes", "more than the 321 left"});
    // Found by fuzz_exr_read: a channel list shorter than its declared size. OpenEXR reads the list
    // by its own length, so it took the following bytes for the next attributes' sizes (one of
    // them 1.9 GB).
    expectFailure(cli("compare '" SS_SOURCE_DIR "/tests/fuzz/corpus/exr/chlist_shorter_than_declared.exr'"),
                  {"chlist_shorter_than_declared.exr", "attribute 'channels' of type 'chlist' declares 236 bytes",
                   "its value takes 165"});
    fs::remove_all(dir);
}

// 7. Bad setting values pass silently.
TEST(CliReliability, SettingValuesMustBeFiniteAndInRange) {
    fs::path dir = tempDir("i14_07");
    writeFile(dir / "s.json", sceneJson(disk("Key")));
    writeFile(dir / "out.exr", "old");
    std::string render = "render " + q(dir / "s.json") + " -o " + q(dir / "out.exr");
    expectFailure(cli(render + " -m shadow_map --set bias=nan"), {"'bias' = 'nan'", "not a finite number"});
    expectFailure(cli(render + " -m shadow_map --set bias=inf"), {"'bias' = 'inf'", "not a finite number"});
    expectFailure(cli(render + " -m shadow_map --set slope_bias=nan"), {"'slope_bias'", "finite"});
    expectFailure(cli(render + " -m shadow_map --set bias=-1"), {"'bias' = '-1'", "out of range 0..1000"});
    expectFailure(cli(render + " -m shadow_map --set bias=1 --set bias=2"), {"setting 'bias' is given twice"});
    expectFailure(cli(render + " -m shadow_map --set shadow_map_size=nan"), {"'shadow_map_size'", "not a finite number"});
    for (const char* v : {"1e30", "-100", "0.5", "100000"})
        expectFailure(cli(render + " -m shadow_map --set shadow_map_size=" + v),
                      {"'shadow_map_size'", "is out of range 0 or 16..8192"});
    expectFailure(cli(render + " -m pcss --set max_search=-1"), {"'max_search' = '-1'", "out of range 0..1"});
    expectFailure(cli(render + " -m reference --set threads=-3"), {"'threads'", "out of range 0..1024"});
    for (const char* blend : {"-5", "2"}) {
        writeFile(dir / "spot.json", sceneJson(R"({"name":"Spot","type":"spot","position":[0,0,4],"direction":[0,0,-1],"radius":0.2,"spot_size":1.0,"spot_blend":)" +
                                               std::string(blend) + "}"));
        expectFailure(cli("render " + q(dir / "spot.json") + " -m shadow_map -o " + q(dir / "out.exr")),
                      {"lights[0]", "spot blend must be in [0, 1]"});
    }
    EXPECT_EQ(readFile(dir / "out.exr"), "old");
    fs::remove_all(dir);
}

// 8. Long light names lose passes.
TEST(CliReliability, LongLightNamesAreRefusedNotCut) {
    fs::path dir = tempDir("i14_08");
    std::string longName(235, 'L');
    writeFile(dir / "s.json", sceneJson(disk(longName)));
    writeFile(dir / "out.exr", "old");
    expectFailure(cli("render " + q(dir / "s.json") + " -m shadow_map -o " + q(dir / "out.exr")),
                  {"lights[0]", "235 bytes long", "at most 131"});
    EXPECT_EQ(readFile(dir / "out.exr"), "old");
    // 131 bytes, the longest allowed (Blender's instance "<parent>/<object>.NNN"), with the
    // longest view layer: every pass arrives under its own, whole name.
    std::string longest(131, 'L');
    std::string text = sceneJson(disk(longest));
    text.insert(1, R"("view_layer":")" + std::string(63, 'V') + R"(",)");
    writeFile(dir / "ok.json", text);
    CliRun r = cli("render " + q(dir / "ok.json") + " -m shadow_map -o " + q(dir / "ok.exr"));
    ASSERT_EQ(r.code, 0) << r.err;
    ss::ExrContents c = ss::readMultilayerExr((dir / "ok.exr").string());
    EXPECT_GE(c.passes.size(), 5u);
    for (const ss::ExrPass& p : c.passes) EXPECT_EQ(p.layer, std::string(63, 'V'));
    EXPECT_TRUE(c.find(longest + "_shadow_map"));
    EXPECT_TRUE(c.find(longest + "_shadow_map_mask"));
    fs::remove_all(dir);
}

// 9. compare reports a perfect score with nothing compared.
TEST(CliReliability, CompareRefusesAnEmptyMask) {
    fs::path dir = tempDir("i14_09");
    ss::Image a(8, 2, 1.0f), b(8, 2, 0.0f), zero(8, 2, 0.0f), nan(8, 2, std::nanf(""));
    ss::writeMultilayerExr((dir / "a.exr").string(), "ViewLayer",
                           {{"L_reference", &a}, {"Z", &zero}, {"N", &nan}});
    ss::writeMultilayerExr((dir / "b.exr").string(), "ViewLayer", {{"L_shadow_map", &b}});
    std::string files = q(dir / "a.exr") + " " + q(dir / "b.exr");
    expectFailure(cli("compare " + files + " --mask Z"), {"mask 'Z' selects no pixel", "nothing to compare"});
    expectFailure(cli("compare " + files + " --mask N"), {"mask 'N' selects no pixel"});
    CliRun ok = cli("compare " + files + " --mask none --json");
    ASSERT_EQ(ok.code, 0) << ok.err;
    EXPECT_EQ(nlohmann::json::parse(ok.out)[0]["pixels"], 16);
    fs::remove_all(dir);
}

bool hasTemporaryFile(const fs::path& dir) {
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().rfind(".ss", 0) == 0 && e.path().filename().string().find(".tmp") != std::string::npos)
            return true;
    return false;
}

// 10. Temporary files stay behind after SIGINT/SIGTERM; a long valid name fails.
TEST(CliReliability, SignalsRemoveTemporaryFilesAndLongNamesWork) {
    fs::path dir = tempDir("i14_10");
    writeFile(dir / "s.json", sceneJson(disk("Key")));
    std::string name = std::string(251, 'o') + ".exr";  // 255 bytes: the longest a folder takes
    CliRun r = cli("render " + q(dir / "s.json") + " -m shadow_map -o " + q(dir / name));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / name));
    // A big EXR takes long enough to write that SIGTERM lands while its temporary file exists.
    writeFile(dir / "big.json", sceneJson(disk("Key"), 4096, 4096));
    writeFile(dir / "out.exr", "old");
    SignalledRun run = signalWhileWriting(
        {"render", (dir / "big.json").string(), "-m", "shadow_map", "-o", (dir / "out.exr").string()}, SIGTERM,
        [&] { return hasTemporaryFile(dir); });
    ASSERT_TRUE(run.signalled) << "the write finished before the test saw its temporary file";
    EXPECT_TRUE(WIFSIGNALED(run.status) && WTERMSIG(run.status) == SIGTERM);
    EXPECT_FALSE(hasTemporaryFile(dir));
    EXPECT_EQ(readFile(dir / "out.exr"), "old");
    fs::remove_all(dir);
}

// 12. The smaller ones.
TEST(CliReliability, MalformedScenesPathsAndRepeatedOptionsFailNamingTheProblem) {
    fs::path dir = tempDir("i14_12");
    std::string tail = " -m shadow_map -o " + q(dir / "out.exr");
    auto sceneFile = [&](const std::string& file, const std::string& text) {
        writeFile(dir / file, text);
        return "render " + q(dir / file) + tail;
    };
    // 1e999 names its JSON path.
    expectFailure(cli(sceneFile("big_number.json", sceneJson(disk("Key", R"(,"radius":1e999)")))),
                  {"big_number.json", "lights[0].radius", "number overflow"});
    // A NUL in a JSON string.
    expectFailure(cli(sceneFile("nul.json", sceneJson(disk(std::string("Ke\0y", 4))))),
                  {"lights[0].name", "NUL character"});
    // Duplicate keys.
    expectFailure(cli(sceneFile("dup.json", sceneJson(disk("Key", R"(,"size":2)")))),
                  {"lights[0].size", "appears twice"});
    // Names with escape sequences are shown escaped.
    CliRun esc = cli(sceneFile("esc.json", sceneJson(disk("a\x1b[31mred"))));
    expectFailure(esc, {"'a\\x1B[31mred'", "control character"});
    EXPECT_EQ(esc.err.find('\x1b'), std::string::npos);
    // render --help is help.
    CliRun help = cli("render --help");
    EXPECT_EQ(help.code, 0);
    EXPECT_NE(help.out.find("usage: softshadow"), std::string::npos);
    // A path too long and a symlink loop say so.
    expectFailure(cli("render " + q(dir / (std::string(300, 'x') + ".json")) + tail), {"path is too long"});
    fs::create_symlink("loop_b.json", dir / "loop_a.json");
    fs::create_symlink("loop_a.json", dir / "loop_b.json");
    expectFailure(cli("render " + q(dir / "loop_a.json") + tail), {"loop_a.json", "symlinks form a loop"});
    // External mesh files: a folder, absolute paths, '..' and /dev/zero.
    auto external = [&](const std::string& file, const std::string& positions) {
        return sceneFile(file, R"({"format":"softshadow-scene","version":1,
          "camera":{"look_from":[3,-3,3],"look_at":[0,0,0],"width":8,"height":8},
          "lights":[{"name":"Key","type":"disk","position":[0,0,4],"direction":[0,0,-1],"size":0.5}],
          "meshes":[{"name":"M","positions_file":)" + nlohmann::json(positions).dump() + R"(,"triangles_file":"t.u32"}]})");
    };
    expectFailure(cli(external("dot.json", ".")), {"meshes[0].positions_file", "is a folder"});
    expectFailure(cli(external("zero.json", "/dev/zero")), {"meshes[0].positions_file", "absolute path"});
    expectFailure(cli(external("up.json", "../p.f32")), {"meshes[0].positions_file", "leaves the scene's folder"});
    fs::create_symlink("/dev/zero", dir / "zero.f32");
    expectFailure(cli(external("link.json", "zero.f32")), {"meshes[0].positions_file", "out of the scene's folder"});
    // Repeated single-value options.
    expectFailure(cli(sceneFile("ok.json", sceneJson(disk("Key"))) + " -o " + q(dir / "b.exr")),
                  {"option -o is given 2 times"});
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
    EXPECT_FALSE(fs::exists(dir / "b.exr"));
    EXPECT_FALSE(hasTemporaryFile(dir));
    fs::remove_all(dir);
}

}  // namespace
