// Whether the reliability rules that live below the command hold in the library: the
// shadow-map cache stays within its budget (least recently used first), progress callbacks
// cannot deadlock the library, and names and view layers are checked where they enter.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/exr_file.h"
#include "io/scene_file.h"
#include "methods/method.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

namespace fs = std::filesystem;

// 4. Memory grows without bound with lights: every light's shadow map stayed cached.
TEST(LibraryReliability, ShadowMapCacheStaysWithinItsBudget) {
    Scene scene;
    scene.addMesh(test::makeGround(4.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addMesh(test::makeBox({-0.5f, -0.5f, 0.6f}, {0.5f, 0.5f, 1.0f}, SS_MESH_CAST | SS_MESH_RECEIVE));
    const int lights = 12;
    for (int i = 0; i < lights; ++i) {
        std::string name = std::to_string(i);
        name.insert(0, 1, 'L');  // (not "L" + ...: GCC 12 warns falsely on it, -Wrestrict)
        scene.addLight(test::makeDiskLight({-1.5f + 0.25f * float(i), 0.3f, 4.0f}, 0.5f, name));
    }
    scene.setCamera(test::makeTopCamera(48, 36));
    const size_t mapBytes = size_t(256) * 256 * 8;  // R32F distance + 32-bit depth
    Renderer renderer(SS_BACKEND_AUTO);
    renderer.setShadowMapBudget(4 * mapBytes);
    RenderSettings settings;
    settings.options = {{"shadow_map_size", "256"}};
    Image firstV = *renderer.render(scene, 0, "shadow_map", settings, nullptr).find("V");
    for (int i = 1; i < lights; ++i) renderer.render(scene, i, "shadow_map", settings, nullptr);
    Renderer::CacheStats s = renderer.cacheStats();
    EXPECT_EQ(s.shadowMaps, lights);
    // Trimmed to 4 maps before each render, one more drawn during it.
    EXPECT_EQ(s.shadowMapBytesPeak, 5 * mapBytes);
    EXPECT_EQ(s.shadowMapsEvicted, lights - 5);  // from the sixth render on, one per render
    // Light 11 was used last: still cached. Light 0 was evicted: drawn again, same picture.
    renderer.render(scene, lights - 1, "shadow_map", settings, nullptr);
    EXPECT_EQ(renderer.cacheStats().shadowMaps, lights);
    Layers again = renderer.render(scene, 0, "shadow_map", settings, nullptr);
    EXPECT_EQ(renderer.cacheStats().shadowMaps, lights + 1);
    EXPECT_EQ(again.find("V")->pixels, firstV.pixels);
}

struct Reentry {
    ss_context* context = nullptr;
    const ss_scene* scene = nullptr;
    ss_status renderStatus = SS_OK, infoStatus = SS_OK;
    std::string renderError, destroyError;
    bool tried = false;
};

int reenter(void* user, float, const char*) {
    auto* r = static_cast<Reentry*>(user);
    if (r->tried) return 0;
    r->tried = true;
    ss_result* out = nullptr;
    r->renderStatus = ss_render(r->context, r->scene, 0, "shadow_map", nullptr, &out);
    r->renderError = ss_last_error();
    char buffer[4096];
    r->infoStatus = ss_context_info(r->context, buffer, sizeof buffer);
    ss_context_destroy(r->context);  // refused: the context stays alive
    r->destroyError = ss_last_error();
    ss_shutdown();  // refused too
    return 0;
}

// 11. Calling the library from its own progress callback deadlocks.
TEST(LibraryReliability, ProgressCallbackCannotReenterItsContext) {
    ss_scene* scene = nullptr;
    fs::path dir = fs::temp_directory_path() / ("ss_i14_11_" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "s.json") << R"({"format":"softshadow-scene","version":1,
      "camera":{"look_from":[3,-3,3],"look_at":[0,0,0],"width":16,"height":12},
      "lights":[{"name":"Key","type":"disk","position":[0,0,4],"direction":[0,0,-1],"size":0.5}],
      "meshes":[{"name":"Ground","primitive":{"type":"plane","size":6}}]})";
    ASSERT_EQ(ss_scene_load((dir / "s.json").c_str(), &scene), SS_OK) << ss_last_error();
    ss_context* context = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &context), SS_OK);
    Reentry r;
    r.context = context;
    r.scene = scene;
    ss_render_options options;
    ss_render_options_default(&options);
    options.progress = reenter;
    options.progress_user = &r;
    ss_result* result = nullptr;
    ASSERT_EQ(ss_render(context, scene, 0, "shadow_map", &options, &result), SS_OK) << ss_last_error();
    EXPECT_TRUE(r.tried);
    EXPECT_EQ(r.renderStatus, SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(r.renderError.find("ss_render: called from a progress callback"), std::string::npos) << r.renderError;
    EXPECT_EQ(r.infoStatus, SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(r.destroyError.find("ss_context_destroy"), std::string::npos) << r.destroyError;
    // The context survived and still renders.
    ss_result* second = nullptr;
    EXPECT_EQ(ss_render(context, scene, 0, "shadow_map", nullptr, &second), SS_OK) << ss_last_error();
    ss_result_destroy(second);
    ss_result_destroy(result);
    ss_context_destroy(context);
    ss_scene_destroy(scene);
    fs::remove_all(dir);
}

// 8 and 12, through the C API: names are checked where they enter, view layers alike everywhere.
TEST(LibraryReliability, CApiChecksNamesAndViewLayers) {
    ss_scene* scene = nullptr;
    ASSERT_EQ(ss_scene_create(&scene), SS_OK);
    ss_light_desc light{};
    for (int i = 0; i < 16; ++i) light.light_to_world[i] = (i % 5 == 0) ? 1.0f : 0.0f;
    light.type = SS_LIGHT_DISK;
    light.size = light.size_y = 1.0f;
    light.cast_shadows = 1;
    std::string tooLong(132, 'x');
    light.name = tooLong.c_str();
    EXPECT_EQ(ss_scene_add_light(scene, &light, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_NE(std::string(ss_last_error()).find("132 bytes long (at most 131)"), std::string::npos) << ss_last_error();
    light.name = "bad\xff\xfe";
    EXPECT_EQ(ss_scene_add_light(scene, &light, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_NE(std::string(ss_last_error()).find("'bad\\xFF\\xFE' is not valid UTF-8"), std::string::npos) << ss_last_error();
    EXPECT_EQ(ss_scene_set_view_layer(scene, "a.b"), SS_ERROR_INVALID_ARGUMENT);
    // ss_write_exr refuses the same view layer before looking at anything else.
    fs::path out = fs::temp_directory_path() / ("ss_i14_12_" + std::to_string(getpid()) + ".exr");
    ss_result* fake = reinterpret_cast<ss_result*>(0x1);  // never read: the view layer fails first
    EXPECT_EQ(ss_write_exr(out.c_str(), "a.b", &fake, 1), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ss_last_error()).find("view layer name 'a.b' has a dot"), std::string::npos) << ss_last_error();
    EXPECT_FALSE(fs::exists(out));
    ss_scene_destroy(scene);
}

// 10. The temporary file of a write is gone when a signal handler calls ss_remove_temporary_files.
TEST(LibraryReliability, RemoveTemporaryFilesUnlinksWritesInProgress) {
    fs::path dir = fs::temp_directory_path() / ("ss_i14_10_" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "out.bin") << "old";
    std::string seen;
    EXPECT_THROW(writeAtomically((dir / "out.bin").string(),
                                 [&](const std::string& temp) {
                                     std::ofstream(temp) << "partial";
                                     seen = temp;
                                     ss_remove_temporary_files();
                                     EXPECT_FALSE(fs::exists(temp));
                                     throw std::runtime_error("interrupted");
                                 }),
                 Error);
    EXPECT_FALSE(seen.empty());
    EXPECT_LE(fs::path(seen).filename().string().size(), 32u);  // short, whatever the target's name
    std::ifstream in(dir / "out.bin");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "old");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace ss

namespace ss {
namespace {

// 4, the output side: results gathered one by one through ss_exr_writer make the same EXR as
// ss_write_exr with all of them in memory, and an unfinished writer leaves no file.
TEST(LibraryReliability, ExrWriterGathersResultsOneByOne) {
    fs::path dir = fs::temp_directory_path() / ("ss_i14_04_" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "s.json") << R"({"format":"softshadow-scene","version":1,
      "camera":{"look_from":[3,-3,3],"look_at":[0,0,0],"width":40,"height":30},
      "lights":[{"name":"A","type":"disk","position":[0,0,4],"direction":[0,0,-1],"size":0.5},
                {"name":"B","type":"disk","position":[1,0,4],"direction":[0,0,-1],"size":0.3}],
      "meshes":[{"name":"Ground","primitive":{"type":"plane","size":6}},
                {"name":"Box","primitive":{"type":"box","size":1},"translate":[0,0,1]}]})";
    ss_scene* scene = nullptr;
    ASSERT_EQ(ss_scene_load((dir / "s.json").c_str(), &scene), SS_OK) << ss_last_error();
    ss_context* context = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &context), SS_OK);
    std::vector<ss_result*> results;
    ss_exr_writer* writer = nullptr;
    ASSERT_EQ(ss_exr_writer_create((dir / "gathered.exr").c_str(), "Layer", &writer), SS_OK) << ss_last_error();
    for (int light = 0; light < 2; ++light)
        for (const char* method : {"shadow_map", "pcss"}) {
            ss_result* r = nullptr;
            ASSERT_EQ(ss_render(context, scene, light, method, nullptr, &r), SS_OK) << ss_last_error();
            ASSERT_EQ(ss_exr_writer_add(writer, r), SS_OK) << ss_last_error();
            results.push_back(r);
        }
    EXPECT_EQ(ss_exr_writer_add(writer, results[0]), SS_ERROR_INVALID_ARGUMENT);  // its passes again
    EXPECT_NE(std::string(ss_last_error()).find("appears twice"), std::string::npos) << ss_last_error();
    ASSERT_EQ(ss_exr_writer_finish(writer), SS_OK) << ss_last_error();
    ss_exr_writer_destroy(writer);
    ASSERT_EQ(ss_write_exr((dir / "at_once.exr").c_str(), "Layer", results.data(), int32_t(results.size())), SS_OK);
    ExrContents gathered = readMultilayerExr((dir / "gathered.exr").string());
    ExrContents atOnce = readMultilayerExr((dir / "at_once.exr").string());
    ASSERT_EQ(gathered.passes.size(), atOnce.passes.size());
    ASSERT_GE(gathered.passes.size(), 8u);
    for (size_t i = 0; i < atOnce.passes.size(); ++i) {
        const ExrPass* g = gathered.find(atOnce.passes[i].pass);
        ASSERT_TRUE(g) << atOnce.passes[i].pass;
        EXPECT_EQ(g->layer, "Layer");
        EXPECT_EQ(g->image.pixels, atOnce.passes[i].image.pixels) << atOnce.passes[i].pass;
    }
    // Unfinished: no EXR, no spool, the old file as it was.
    std::ofstream(dir / "old.exr") << "old";
    ASSERT_EQ(ss_exr_writer_create((dir / "old.exr").c_str(), "Layer", &writer), SS_OK);
    ASSERT_EQ(ss_exr_writer_add(writer, results[0]), SS_OK);
    ss_exr_writer_destroy(writer);
    std::ifstream in(dir / "old.exr");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "old");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 4);  // s, gathered, at_once, old
    // A path that cannot take an EXR fails at create, before any render.
    EXPECT_EQ(ss_exr_writer_create("/dev/null", "Layer", &writer), SS_ERROR_IO);
    EXPECT_NE(std::string(ss_last_error()).find("character device"), std::string::npos) << ss_last_error();
    EXPECT_EQ(writer, nullptr);
    for (ss_result* r : results) ss_result_destroy(r);
    ss_context_destroy(context);
    ss_scene_destroy(scene);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace ss

namespace ss {
namespace {

// 12, the loader's own guards: deep nesting stops before the stack does, and a bad number deep
// in an array names its element.
TEST(LibraryReliability, SceneLoaderNamesPathsAndLimitsNesting) {
    std::string deep = R"({"format":"softshadow-scene","version":1,"metadata":)" + std::string(100, '[') +
                       std::string(100, ']') + "}";
    try {
        parseSceneText(deep, ".", "deep.json");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_IO);
        EXPECT_NE(std::string(e.what()).find("deep.json"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("nesting deeper than 64 levels"), std::string::npos) << e.what();
    }
    std::string overflow = R"({"format":"softshadow-scene","version":1,
      "meshes":[{"name":"M","positions":[0,0,0, 1,0,0, 0,1e999,0],"triangles":[0,1,2]}]})";
    try {
        parseSceneText(overflow, ".", "big.json");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("big.json': meshes[0].positions[7]: malformed JSON: number overflow"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace ss
