// Whether the reproducers of issue 29 run through the `softshadow` command get one clear error
// before anything renders (names, limits, inputs), and whether a killed writer's temporary file
// goes at the next write into its folder.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <regex>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_run.h"

extern char** environ;

namespace {

void writeFile(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string scene(const std::string& lightsJson, int w = 32, int h = 24) {
    return R"({"format":"softshadow-scene","version":1,
      "camera":{"look_from":[3,-3,3],"look_at":[0,0,0],"fov_y_degrees":40,"width":)" + std::to_string(w) +
           R"(,"height":)" + std::to_string(h) + R"(},
      "lights":[)" + lightsJson + R"(],
      "meshes":[{"name":"Tet","positions":[0,0,0, 1,0,0, 0,1,0, 0,0,1],"triangles":[0,2,1, 0,1,3, 1,2,3, 0,3,2]},
                {"name":"Ground","primitive":{"type":"plane","size":6}}]})";
}
std::string disk(const std::string& name, double x = 0) {
    return R"({"name":)" + nlohmann::json(name).dump() + R"(,"type":"disk","position":[)" + std::to_string(x) +
           R"(,0,4],"direction":[0,0,-1],"size":0.5})";
}
std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

std::vector<fs::path> temporaryFiles(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().rfind(".ss", 0) == 0) out.push_back(e.path());
    return out;
}

// The pid of a process that has ended (and been reaped).
pid_t deadPid() {
    pid_t pid = fork();
    if (pid == 0) _exit(0);
    waitpid(pid, nullptr, 0);
    return pid;
}

// 4. Lights "A.B" and "A_B" (or "A B") write the same passes: refused when the scene loads.
TEST(CliNamesFilesLimits, PassNameCollisionNamesBothLightsBeforeRendering) {
    fs::path dir = tempDir("i29_04");
    writeFile(dir / "s.json", scene(disk("A.B", -1) + "," + disk("Fill") + "," + disk("A_B", 1)));
    CliRun r = cli("render " + q(dir / "s.json") + " -m shadow_map -o " + q(dir / "out.exr"));
    expectFailure(r, {"s.json", "'A.B'", "'A_B'", "same passes"});
    writeFile(dir / "s2.json", scene(disk("A B", -1) + "," + disk("A_B", 1)));
    expectFailure(cli("render " + q(dir / "s2.json") + " -m shadow_map -o " + q(dir / "out.exr")), {"'A B'", "'A_B'"});
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
    EXPECT_TRUE(temporaryFiles(dir).empty());
    fs::remove_all(dir);
}

// 10. Control (C1) and bidirectional formatting characters, as docs/scene-format.md refuses them.
TEST(CliNamesFilesLimits, ControlAndBidiNamesAreRefusedAndCompareSaysNotAnExr) {
    fs::path dir = tempDir("i29_10");
    for (const std::string& name : {std::string("csi\u009b2J"), std::string("evil\u202etxt.exr"),
                                    std::string("iso\u2066x")}) {
        writeFile(dir / "s.json", scene(disk(name)));
        CliRun r = cli("render " + q(dir / "s.json") + " -m shadow_map -o " + q(dir / "out.exr"));
        expectFailure(r, {"light name", "a bidirectional formatting character"});
        EXPECT_EQ(r.err.find(name), std::string::npos) << "shown raw: " << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
    // A JSON file is no EXR: compare says so (it used to say "it holds deep data").
    writeFile(dir / "s.json", scene(disk("Key")));
    expectFailure(cli("compare " + q(dir / "s.json")), {"s.json", "not an OpenEXR file"});
    writeFile(dir / "short.exr", "v/1");
    expectFailure(cli("compare " + q(dir / "short.exr")), {"too short"});
    fs::remove_all(dir);
}

// 11. Sides up to 16384 (the documented limit, the texture size of every OpenGL 4.5 context).
TEST(CliNamesFilesLimits, DocumentedSideLimitIsTheOneChecked) {
    fs::path dir = tempDir("i29_11");
    writeFile(dir / "wide.json", scene(disk("Key"), 32768, 4));
    expectFailure(cli("render " + q(dir / "wide.json") + " -m shadow_map -o " + q(dir / "out.exr")),
                  {"wide.json", "16384"});
    writeFile(dir / "s.json", scene(disk("Key"), 16384, 4));
    CliRun ok = cli("render " + q(dir / "s.json") + " -m shadow_map -o " + q(dir / "out.exr"));
    EXPECT_EQ(ok.code, 0) << ok.err;
    expectFailure(cli("render " + q(dir / "s.json") + " -m shadow_map --width 16385 -o " + q(dir / "o2.exr")),
                  {"16385x4", "1..16384"});
    EXPECT_FALSE(fs::exists(dir / "o2.exr"));
    fs::remove_all(dir);
}

// 5. SIGKILL leaves the temporary file (nothing can run then); the next write into the folder
// removes it, and only the files of processes that are gone from this host.
TEST(CliNamesFilesLimits, AKilledWritersTemporaryFileGoesAtTheNextWrite) {
    fs::path dir = tempDir("i29_05");
    writeFile(dir / "big.json", scene(disk("Key"), 4096, 4096));
    SignalledRun run = signalWhileWriting(
        {"render", (dir / "big.json").string(), "-m", "shadow_map", "-o", (dir / "out.exr").string()}, SIGKILL,
        [&] { return !temporaryFiles(dir).empty(); });
    const pid_t pid = run.pid;
    ASSERT_TRUE(run.signalled) << "the write finished before the test saw its temporary file";
    ASSERT_TRUE(WIFSIGNALED(run.status) && WTERMSIG(run.status) == SIGKILL);
    std::vector<fs::path> left = temporaryFiles(dir);
    ASSERT_EQ(left.size(), 1u);
    EXPECT_FALSE(fs::exists(dir / "out.exr"));  // the final name never holds a half file
    // ".ss<pid>-<tag>_<n>.tmp.exr": the same name with a live pid (this test's), another host's
    // tag, and an earlier version's untagged names (fresh, and an hour old) beside it.
    std::smatch m;
    std::string name = left[0].filename().string();
    ASSERT_TRUE(std::regex_match(name, m, std::regex(R"(\.ss(\d+)-([0-9a-f]{8})_(\d+)\.tmp\.exr)"))) << name;
    EXPECT_EQ(m[1].str(), std::to_string(pid));
    std::string tag = m[2].str(), otherTag = tag == "00000000" ? "11111111" : "00000000";
    std::string dead = std::to_string(deadPid()), live = std::to_string(getpid());
    writeFile(dir / (".ss" + live + "-" + tag + "_0.tmp.exr"), "live");
    writeFile(dir / (".ss" + dead + "-" + otherTag + "_0.tmp.exr"), "elsewhere");
    writeFile(dir / (".ss" + dead + "_7.tmp.exr"), "fresh legacy");
    writeFile(dir / (".ss" + dead + "_8.tmp.exr"), "old legacy");
    fs::last_write_time(dir / (".ss" + dead + "_8.tmp.exr"), fs::file_time_type::clock::now() - std::chrono::hours(2));
    writeFile(dir / "small.json", scene(disk("Key")));
    CliRun r = cli("render " + q(dir / "small.json") + " -m shadow_map -o " + q(dir / "out.exr"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(fs::exists(left[0])) << "the killed writer's file is still there";
    EXPECT_TRUE(fs::exists(dir / (".ss" + live + "-" + tag + "_0.tmp.exr")));
    EXPECT_TRUE(fs::exists(dir / (".ss" + dead + "-" + otherTag + "_0.tmp.exr")));
    EXPECT_TRUE(fs::exists(dir / (".ss" + dead + "_7.tmp.exr")));
    EXPECT_FALSE(fs::exists(dir / (".ss" + dead + "_8.tmp.exr")));
    EXPECT_EQ(temporaryFiles(dir).size(), 3u);
    fs::remove_all(dir);
}

}  // namespace
