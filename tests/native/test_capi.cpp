// Whether the C API reports every bad input with a status and a message naming the problem,
// never lets an exception out, keeps its last error per thread, and renders and writes EXRs.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <atomic>
#include <chrono>
#include <string>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "capi/capi_internal.h"
#include "io/exr_file.h"
#include "renderer/cache_stats.h"
#include "softshadow/softshadow.h"

namespace {

namespace fs = std::filesystem;

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("ss_capi_" + std::to_string(getpid()) + "_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

bool errorHas(const std::string& fragment) {
    return std::string(ss_last_error()).find(fragment) != std::string::npos;
}

// A tetrahedron: 4 vertices, 4 outward faces.
const float kTet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const uint32_t kTetFaces[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};

void identity(float m[16]) {
    for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0f : 0.0f;
}

ss_light_desc diskLight(const char* name, float size) {
    ss_light_desc d{};
    d.name = name;
    d.type = SS_LIGHT_DISK;
    identity(d.light_to_world);
    d.light_to_world[12] = 3.0f;  // at (3, 0, 4), emitting down (-Z), so the box's shadow falls
    d.light_to_world[14] = 4.0f;  // beside it (umbra around x = -1.4) where the camera sees it
    d.size = size;
    d.size_y = size;
    d.cast_shadows = 1;
    return d;
}

// A small scene the reference can render quickly: a box over a ground plane, seen from above.
// Ground point (-1.4, 0, 0) is in the umbra: its lines to every point of the light (radius 0.5
// around (3, 0, 4)) cross the box's slab 1 <= z <= 1.5 within |x|, |y| < 0.5.
ss_scene* smallScene(int w, int h) {
    ss_scene* s = nullptr;
    EXPECT_EQ(ss_scene_create(&s), SS_OK);
    const float ground[12] = {-4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0};
    const uint32_t groundFaces[6] = {0, 1, 2, 0, 2, 3};
    EXPECT_EQ(ss_scene_add_mesh(s, "Ground", ground, 4, groundFaces, 2, nullptr, SS_MESH_CAST | SS_MESH_RECEIVE, nullptr), SS_OK);
    float box[8 * 3];
    for (int i = 0; i < 8; ++i) {
        box[3 * i] = (i & 1) ? 0.5f : -0.5f;
        box[3 * i + 1] = (i & 2) ? 0.5f : -0.5f;
        box[3 * i + 2] = (i & 4) ? 1.5f : 1.0f;
    }
    const uint32_t boxFaces[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                   2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
    EXPECT_EQ(ss_scene_add_mesh(s, "Box", box, 8, boxFaces, 12, nullptr, SS_MESH_CAST | SS_MESH_RECEIVE, nullptr), SS_OK);
    ss_light_desc light = diskLight("Key.001", 1.0f);
    EXPECT_EQ(ss_scene_add_light(s, &light, nullptr), SS_OK);
    ss_camera_desc cam{};
    glm::mat4 view = glm::lookAt(glm::vec3(0, -0.01f, 8), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
    glm::mat4 proj = glm::perspective(glm::radians(50.0f), float(w) / float(h), 0.1f, 100.0f);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) cam.world_to_camera[c * 4 + r] = view[c][r], cam.projection[c * 4 + r] = proj[c][r];
    cam.width = w;
    cam.height = h;
    cam.pixel_aspect = 1.0f;
    EXPECT_EQ(ss_scene_set_camera(s, &cam), SS_OK);
    return s;
}

TEST(CApi, NullPointersAreNamed) {
    EXPECT_EQ(ss_scene_create(nullptr), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("ss_scene_create: out is null")) << ss_last_error();
    ss_scene* s = nullptr;
    ASSERT_EQ(ss_scene_create(&s), SS_OK);
    EXPECT_STREQ(ss_last_error(), "");
    EXPECT_EQ(ss_scene_add_mesh(s, "m", nullptr, 3, kTetFaces, 1, nullptr, SS_MESH_CAST, nullptr), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("xyz is null"));
    EXPECT_EQ(ss_scene_add_light(s, nullptr, nullptr), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_scene_load(nullptr, &s), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(s, nullptr);  // outputs are cleared on failure
    EXPECT_EQ(ss_render(nullptr, nullptr, 0, "reference", nullptr, nullptr), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_write_exr(nullptr, "ViewLayer", nullptr, 0), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_scene_light_name(nullptr, 0), nullptr);
    EXPECT_EQ(ss_scene_light_count(nullptr), 0);
    ss_scene_destroy(nullptr);
    ss_result_destroy(nullptr);
    ss_context_destroy(nullptr);
}

TEST(CApi, NaNVertexIsRejected) {
    ss_scene* s = nullptr;
    ASSERT_EQ(ss_scene_create(&s), SS_OK);
    float xyz[12];
    std::copy(kTet, kTet + 12, xyz);
    xyz[4] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(ss_scene_add_mesh(s, "Bad", xyz, 4, kTetFaces, 4, nullptr, SS_MESH_CAST, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(errorHas("mesh 'Bad'") && errorHas("vertex 1 is not finite")) << ss_last_error();
    EXPECT_EQ(ss_scene_mesh_count(s), 0);
    ss_scene_destroy(s);
}

TEST(CApi, IndexOutOfRangeIsRejected) {
    ss_scene* s = nullptr;
    ASSERT_EQ(ss_scene_create(&s), SS_OK);
    uint32_t faces[12];
    std::copy(kTetFaces, kTetFaces + 12, faces);
    faces[7] = 4;
    EXPECT_EQ(ss_scene_add_mesh(s, "Tet", kTet, 4, faces, 4, nullptr, SS_MESH_CAST, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(errorHas("triangle 2 uses vertex index 4") && errorHas("4 vertices")) << ss_last_error();
    ss_scene_destroy(s);
}

TEST(CApi, ZeroSizeLightIsRejected) {
    ss_scene* s = nullptr;
    ASSERT_EQ(ss_scene_create(&s), SS_OK);
    ss_light_desc d = diskLight("Flat", 0.0f);
    EXPECT_EQ(ss_scene_add_light(s, &d, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(errorHas("light 'Flat'") && errorHas("size greater than zero")) << ss_last_error();
    d.type = ss_light_type(42);
    EXPECT_EQ(ss_scene_add_light(s, &d, nullptr), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_scene_light_count(s), 0);
    ss_scene_destroy(s);
}

TEST(CApi, BadSceneFiles) {
    fs::path dir = tempDir("files");
    ss_scene* s = nullptr;
    std::string missing = (dir / "missing.json").string();
    EXPECT_EQ(ss_scene_load(missing.c_str(), &s), SS_ERROR_IO);
    EXPECT_TRUE(errorHas(missing) && errorHas("does not exist")) << ss_last_error();
    std::ofstream(dir / "bad.json") << "{\"format\": ";
    EXPECT_EQ(ss_scene_load((dir / "bad.json").c_str(), &s), SS_ERROR_IO);
    EXPECT_TRUE(errorHas("bad.json") && errorHas("malformed JSON")) << ss_last_error();
    std::ofstream(dir / "nan.json") << R"({"format":"softshadow-scene","version":1,"meshes":[
        {"name":"m","positions":[0,0,0, 1,0,0, 0,"nan",0],"triangles":[0,1,2]}]})";
    EXPECT_EQ(ss_scene_load((dir / "nan.json").c_str(), &s), SS_ERROR_IO);
    EXPECT_TRUE(errorHas("meshes[0].positions[7]") && errorHas("expected a number")) << ss_last_error();
    EXPECT_EQ(s, nullptr);
    fs::remove_all(dir);
}

TEST(CApi, LastErrorIsPerThread) {
    EXPECT_EQ(ss_scene_create(nullptr), SS_ERROR_INVALID_ARGUMENT);
    std::string other = "unset";
    std::thread([&] { other = ss_last_error(); }).join();
    EXPECT_EQ(other, "");
    EXPECT_TRUE(errorHas("out is null"));
}

TEST(CApi, SceneQueriesAndSaveLoad) {
    fs::path dir = tempDir("save");
    ss_scene* s = smallScene(40, 30);
    ASSERT_EQ(ss_scene_set_view_layer(s, "Main"), SS_OK);
    EXPECT_EQ(ss_scene_set_view_layer(s, "a.b"), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_scene_light_count(s), 1);
    EXPECT_STREQ(ss_scene_light_name(s, 0), "Key.001");
    EXPECT_EQ(ss_scene_light_name(s, 1), nullptr);
    EXPECT_TRUE(errorHas("light index 1 is out of range"));
    char report[512];
    ASSERT_EQ(ss_scene_mesh_report(s, 1, report, sizeof report), SS_OK);
    EXPECT_NE(std::string(report).find("\"closed_manifold\": true"), std::string::npos) << report;
    EXPECT_EQ(ss_scene_mesh_report(s, 0, report, 8), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("buffer holds 8 bytes"));

    std::string path = (dir / "scene.json").string();
    ASSERT_EQ(ss_scene_save(s, path.c_str()), SS_OK) << ss_last_error();
    ss_scene* back = nullptr;
    ASSERT_EQ(ss_scene_load(path.c_str(), &back), SS_OK) << ss_last_error();
    EXPECT_EQ(ss_scene_mesh_count(back), 2);
    EXPECT_STREQ(ss_scene_view_layer(back), "Main");
    ss_light_desc a, b;
    ASSERT_EQ(ss_scene_get_light(s, 0, &a), SS_OK);
    ASSERT_EQ(ss_scene_get_light(back, 0, &b), SS_OK);
    EXPECT_STREQ(a.name, b.name);
    EXPECT_EQ(0, std::memcmp(a.light_to_world, b.light_to_world, sizeof a.light_to_world));
    ss_camera_desc ca, cb;
    ASSERT_EQ(ss_scene_get_camera(s, &ca), SS_OK);
    ASSERT_EQ(ss_scene_get_camera(back, &cb), SS_OK);
    EXPECT_EQ(0, std::memcmp(ca.projection, cb.projection, sizeof ca.projection));
    EXPECT_EQ(cb.width, 40);
    ss_scene_destroy(back);
    ss_scene_destroy(s);
    fs::remove_all(dir);
}

TEST(CApi, WriteExrNamesPassesAndFailsCleanly) {
    fs::path dir = tempDir("exr");
    // Results made by hand: the writer does not care which method produced them.
    ss_result r;
    r.light = "Key.001 lamp";
    r.method = "reference";
    r.requested = "reference";
    r.layers.add("V", ss::Image(6, 4, 0.25f));
    r.layers.add("mask", ss::Image(6, 4, 1.0f));
    const ss_result* list[] = {&r};
    std::string out = (dir / "out.exr").string();
    ASSERT_EQ(ss_write_exr(out.c_str(), "ViewLayer", list, 1), SS_OK) << ss_last_error();
    ss::ExrContents back = ss::readMultilayerExr(out);
    ASSERT_EQ(back.passes.size(), 2u);
    EXPECT_TRUE(back.find("Key_001_lamp_reference"));
    EXPECT_TRUE(back.find("Key_001_lamp_reference_mask"));

    std::string bad = (dir / "no_such_folder" / "out.exr").string();
    EXPECT_EQ(ss_write_exr(bad.c_str(), "ViewLayer", list, 1), SS_ERROR_IO);
    EXPECT_TRUE(errorHas(bad)) << ss_last_error();
    EXPECT_FALSE(fs::exists(dir / "no_such_folder"));
    EXPECT_EQ(ss_write_exr(out.c_str(), "ViewLayer", list, 0), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
    fs::remove_all(dir);
}

TEST(CApi, WriteExrKeepsAutoPassNamesAndRecordsTheMethodThatRan) {
    fs::path dir = tempDir("exr-auto");
    ss_result r;
    r.light = "Key Light";
    r.method = "pcss";
    r.requested = "auto";
    r.layers.add("V", ss::Image(6, 4, 0.5f));
    r.layers.add("mask", ss::Image(6, 4, 1.0f));
    const ss_result* list[] = {&r};
    std::string out = (dir / "auto.exr").string();
    ASSERT_EQ(ss_write_exr(out.c_str(), "ViewLayer", list, 1), SS_OK) << ss_last_error();
    ss::ExrContents back = ss::readMultilayerExr(out);
    ASSERT_EQ(back.passes.size(), 2u);
    EXPECT_TRUE(back.find("Key_Light_auto"));
    EXPECT_TRUE(back.find("Key_Light_auto_mask"));
    auto in = OIIO::ImageInput::open(out);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute(ss::kExrMethodsAttribute), "Key_Light_auto=pcss");
    in->close();
    fs::remove_all(dir);
}

// What the CLI's `render` needs before and around the EXR: checks of the output and its shape,
// and previews that replace their old files only after the EXR is written.
TEST(CApi, OutputChecksAndStagedPreviews) {
    fs::path dir = tempDir("staged");
    std::string out = (dir / "out.exr").string();
    EXPECT_EQ(ss_check_output_path(out.c_str()), SS_OK) << ss_last_error();
    std::string missing = (dir / "no_such_folder" / "out.exr").string();
    EXPECT_EQ(ss_check_output_path(missing.c_str()), SS_ERROR_IO);
    EXPECT_TRUE(errorHas(missing)) << ss_last_error();
    EXPECT_EQ(ss_check_output_path(dir.string().c_str()), SS_ERROR_IO);  // a folder is not a file
    EXPECT_EQ(ss_check_exr_shape(out.c_str(), 2, 64), SS_OK) << ss_last_error();
    EXPECT_EQ(ss_check_exr_shape(out.c_str(), 1000000, 64), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("cannot write EXR '" + out + "'")) << ss_last_error();
    EXPECT_EQ(ss_check_exr_shape(out.c_str(), -1, 64), SS_ERROR_INVALID_ARGUMENT);

    fs::path png = dir / "png";
    fs::create_directories(png);
    { std::ofstream(png / "Key_pcss.png") << "old"; }
    ss_result r;
    r.light = "Key";
    r.method = "pcss";
    r.requested = "auto";
    r.layers.add("V", ss::Image(6, 4, 0.5f));
    r.layers.add("mask", ss::Image(6, 4, 1.0f));
    {
        // Destroyed before finish: no EXR, the old preview as it was, no temporary file left.
        ss_exr_writer* w = nullptr;
        ASSERT_EQ(ss_exr_writer_create(out.c_str(), "ViewLayer", &w), SS_OK) << ss_last_error();
        ASSERT_EQ(ss_exr_writer_set_preview_folder(w, png.string().c_str()), SS_OK) << ss_last_error();
        ASSERT_EQ(ss_exr_writer_add(w, &r), SS_OK) << ss_last_error();
        ss_exr_writer_destroy(w);
        EXPECT_FALSE(fs::exists(out));
        EXPECT_EQ(fs::file_size(png / "Key_pcss.png"), 3u);
        EXPECT_EQ(std::distance(fs::directory_iterator(png), fs::directory_iterator{}), 1);
    }
    ss_exr_writer* w = nullptr;
    ASSERT_EQ(ss_exr_writer_create(out.c_str(), "ViewLayer", &w), SS_OK) << ss_last_error();
    ASSERT_EQ(ss_exr_writer_set_preview_folder(w, png.string().c_str()), SS_OK) << ss_last_error();
    ASSERT_EQ(ss_exr_writer_add(w, &r), SS_OK) << ss_last_error();
    // Another pass name, the same preview file: "Key/" is made "Key_" inside the folder.
    ss_result slash = r;
    slash.light = "Key/";
    EXPECT_EQ(ss_exr_writer_add(w, &slash), SS_OK) << ss_last_error();
    slash.light = "Key\\";
    EXPECT_EQ(ss_exr_writer_add(w, &slash), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("two passes would share the preview 'Key__pcss.png'")) << ss_last_error();
    ss_exr_writer_destroy(w);
    EXPECT_EQ(fs::file_size(png / "Key_pcss.png"), 3u);

    ASSERT_EQ(ss_exr_writer_create(out.c_str(), "ViewLayer", &w), SS_OK) << ss_last_error();
    ASSERT_EQ(ss_exr_writer_set_preview_folder(w, png.string().c_str()), SS_OK) << ss_last_error();
    ASSERT_EQ(ss_exr_writer_add(w, &r), SS_OK) << ss_last_error();
    ASSERT_EQ(ss_exr_writer_finish(w), SS_OK) << ss_last_error();
    ss_exr_writer_destroy(w);
    // The EXR names the pass as asked (auto); the previews by the method that ran.
    EXPECT_TRUE(ss::readMultilayerExr(out).find("Key_auto"));
    EXPECT_GT(fs::file_size(png / "Key_pcss.png"), 3u);
    EXPECT_TRUE(fs::exists(png / "Key_pcss_mask.png"));
    EXPECT_EQ(std::distance(fs::directory_iterator(png), fs::directory_iterator{}), 2);
    fs::remove_all(dir);
}

TEST(CApi, RenderArgumentsAreChecked) {
    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    EXPECT_EQ(ss_context_create(ss_backend(9), &ctx), SS_ERROR_INVALID_ARGUMENT);
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    ss_scene* s = smallScene(8, 6);
    ss_result* res = nullptr;
    EXPECT_EQ(ss_render(ctx, s, 3, "reference", nullptr, &res), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("light index 3 is out of range"));
    EXPECT_EQ(ss_render(ctx, s, 0, "no_such_method", nullptr, &res), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("no_such_method")) << ss_last_error();
    ss_render_options o;
    ss_render_options_default(&o);
    o.samples = -1;
    EXPECT_EQ(ss_render(ctx, s, 0, "reference", &o, &res), SS_ERROR_INVALID_ARGUMENT);
    o.samples = 0;
    o.settings = "novalue";
    EXPECT_EQ(ss_render(ctx, s, 0, "reference", &o, &res), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(res, nullptr);
    ss_scene_destroy(s);
    ss_context_destroy(ctx);
}

int cancelAtOnce(void*, float, const char*) { return 1; }

TEST(CApi, ReferenceRenderProducesLayersAndExr) {
    fs::path dir = tempDir("render");
    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    ss_scene* s = smallScene(48, 36);
    ss_render_options o;
    ss_render_options_default(&o);
    o.samples = 16;
    ss_result* res = nullptr;
    ASSERT_EQ(ss_render(ctx, s, 0, "reference", &o, &res), SS_OK) << ss_last_error();
    EXPECT_STREQ(ss_result_method(res), "reference");
    EXPECT_STREQ(ss_result_light(res), "Key.001");
    ASSERT_GE(ss_result_layer_count(res), 2);
    const char* name;
    const float* px;
    int32_t w, h;
    ASSERT_EQ(ss_result_layer(res, 0, &name, &px, &w, &h), SS_OK);
    EXPECT_STREQ(name, "V");
    EXPECT_EQ(w, 48);
    EXPECT_EQ(h, 36);
    float lo = 1, hi = 0;
    for (int i = 0; i < w * h; ++i) lo = std::min(lo, px[i]), hi = std::max(hi, px[i]);
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_LT(lo, 0.05f);  // the box's umbra is in the picture
    EXPECT_GT(hi, 0.999f);  // and so is lit ground
    EXPECT_EQ(ss_result_layer(res, 99, &name, &px, &w, &h), SS_ERROR_INVALID_ARGUMENT);

    std::string out = (dir / "r.exr").string();
    const ss_result* list[] = {res};
    ASSERT_EQ(ss_write_exr(out.c_str(), ss_scene_view_layer(s), list, 1), SS_OK) << ss_last_error();
    ss::ExrContents back = ss::readMultilayerExr(out);
    const ss::ExrPass* v = back.find("Key_001_reference");
    ASSERT_TRUE(v);
    EXPECT_EQ(v->layer, "ViewLayer");
    EXPECT_EQ(0, std::memcmp(v->image.pixels.data(), px, sizeof(float) * w * h));

    o.progress = cancelAtOnce;
    ss_result* cancelled = nullptr;
    EXPECT_EQ(ss_render(ctx, s, 0, "reference", &o, &cancelled), SS_ERROR_CANCELLED);
    EXPECT_EQ(cancelled, nullptr);
    ss_result_destroy(res);
    ss_scene_destroy(s);
    ss_context_destroy(ctx);
    fs::remove_all(dir);
}

TEST(CApi, ShadowMapRenderThroughGl) {
    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    char info[4096];
    if (ss_context_info(ctx, info, sizeof info) == SS_ERROR_GL) {
        std::string why = ss_last_error();
        ss_context_destroy(ctx);
        GTEST_SKIP() << "no GL backend: " << why;
    }
    ss_scene* s = smallScene(32, 24);
    ss_result* res = nullptr;
    ASSERT_EQ(ss_render(ctx, s, 0, "auto", nullptr, &res), SS_OK) << ss_last_error();
    EXPECT_STRNE(ss_result_method(res), "auto");  // the output says which method ran
    const float* px;
    ASSERT_EQ(ss_result_layer(res, 0, nullptr, &px, nullptr, nullptr), SS_OK);
    ss_result_destroy(res);
    ss_scene_destroy(s);
    ss_context_destroy(ctx);
}

}  // namespace

namespace {

TEST(CApiContext, DestroyDuringARenderCancelsItAndWaits) {
    // The preview stops its worker by destroying the context from another thread: the render in
    // flight is cancelled (SS_ERROR_CANCELLED) and destroy returns only after it has.
    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    ss_scene* scene = smallScene(64, 48);
    struct Shared {
        std::atomic<bool> started{false};
    } shared;
    ss_render_options o;
    ss_render_options_default(&o);
    o.samples = 4096;  // seconds of tracing: still running when destroy comes
    o.settings = "threads=1";
    o.progress_user = &shared;
    o.progress = [](void* user, float, const char*) {
        static_cast<Shared*>(user)->started = true;
        return 0;
    };
    ss_status status = SS_OK;
    std::thread worker([&] {
        ss_result* r = nullptr;
        status = ss_render(ctx, scene, 0, "reference", &o, &r);
        ss_result_destroy(r);
    });
    while (!shared.started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    auto t0 = std::chrono::steady_clock::now();
    ss_context_destroy(ctx);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    worker.join();
    EXPECT_EQ(status, SS_ERROR_CANCELLED);
    EXPECT_LT(seconds, 5.0) << "the render was not cancelled";
    ss_scene_destroy(scene);
}

TEST(CApiContext, MethodListComesFromTheLibrary) {
    ASSERT_EQ(ss_method_count(), 7);
    std::vector<std::string> names;
    for (int32_t i = 0; i < ss_method_count(); ++i) names.push_back(ss_method_name(i));
    EXPECT_EQ(names, (std::vector<std::string>{"shadow_map", "pcss", "dbuffer", "sweep", "penumbra_map",
                                               "occlusion_textures", "reference"}));
    EXPECT_EQ(ss_method_name(-1), nullptr);
    EXPECT_EQ(ss_method_name(7), nullptr);
}

TEST(CApiContext, EveryCacheCounterIsReadByNameThroughTheCApi) {
    // The counters are declared once (scene_cache/cache_counters.h): each reaches the C API in that
    // order under its name, with what it counts, and reads the renderer's own value.
    std::vector<std::string> declared;
#define SS_NAME(type, member, name, combine, doc) declared.push_back(name);
    SS_CACHE_COUNTERS(SS_NAME)
#undef SS_NAME
    ASSERT_EQ(ss_cache_stat_count(), int32_t(declared.size()));
    std::set<std::string> unique;
    for (int32_t i = 0; i < ss_cache_stat_count(); ++i) {
        const std::string name = ss_cache_stat_name(i);
        EXPECT_EQ(name, declared[size_t(i)]);
        EXPECT_EQ(name.find_first_not_of("abcdefghijklmnopqrstuvwxyz_"), std::string::npos) << name;
        EXPECT_GT(std::strlen(ss_cache_stat_doc(i)), 10u) << name;
        unique.insert(name);
    }
    EXPECT_EQ(unique.size(), declared.size());
    EXPECT_EQ(ss_cache_stat_name(-1), nullptr);
    EXPECT_EQ(ss_cache_stat_name(ss_cache_stat_count()), nullptr);
    EXPECT_EQ(ss_cache_stat_doc(ss_cache_stat_count()), nullptr);

    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    ss_scene* scene = smallScene(32, 24);
    ss_render_options o;
    ss_render_options_default(&o);
    o.samples = 4;
    for (const char* method : {"shadow_map", "reference"}) {
        ss_result* r = nullptr;
        ASSERT_EQ(ss_render(ctx, scene, 0, method, &o, &r), SS_OK) << ss_last_error();
        ss_result_destroy(r);
    }
    const ss::CacheStats s = ctx->renderer.cacheStats();
    EXPECT_EQ(s.sceneCaches, 1);
    EXPECT_EQ(s.meshUploads, 2);
    EXPECT_EQ(s.traceSceneBuilds, 1);
#define SS_CHECK(type, member, name, combine, doc)                       \
    {                                                                    \
        double value = -1.0;                                             \
        EXPECT_EQ(ss_context_cache_stat(ctx, name, &value), SS_OK) << name; \
        EXPECT_EQ(value, double(s.member)) << name;                      \
    }
    SS_CACHE_COUNTERS(SS_CHECK)
#undef SS_CHECK
    double value = -1.0;
    EXPECT_EQ(ss_context_cache_stat(ctx, "mesh_upload", &value), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("unknown cache stat 'mesh_upload'") && errorHas("mesh_uploads, ")) << ss_last_error();
    EXPECT_EQ(value, -1.0);
    EXPECT_EQ(ss_context_cache_stat(ctx, nullptr, &value), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_context_cache_stat(ctx, "frames", nullptr), SS_ERROR_INVALID_ARGUMENT);
    ss_scene_destroy(scene);
    ss_context_destroy(ctx);
}

TEST(CApiContext, UnknownSettingKeyIsRefusedNamingIt) {
    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    ss_scene* scene = smallScene(32, 24);
    ss_render_options o;
    ss_render_options_default(&o);
    o.settings = "blocker_sample=64";
    ss_result* r = nullptr;
    EXPECT_EQ(ss_render(ctx, scene, 0, "pcss", &o, &r), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(r, nullptr);
    EXPECT_TRUE(errorHas("no setting 'blocker_sample'")) << ss_last_error();
    EXPECT_TRUE(errorHas("blocker_samples, pcf_samples")) << ss_last_error();
    ss_scene_destroy(scene);
    ss_context_destroy(ctx);
}

}  // namespace

namespace {

TEST(CApiImages, PassNamesAndComparisonsForTheCli) {
    char name[64];
    ASSERT_EQ(ss_pass_name("Area.001 key", "shadow_map", "mask", name, sizeof name), SS_OK);
    EXPECT_STREQ(name, "Area_001_key_shadow_map_mask");
    ASSERT_EQ(ss_pass_name("Key", "pcss", "V", name, sizeof name), SS_OK);
    EXPECT_STREQ(name, "Key_pcss");
    EXPECT_EQ(ss_pass_name("Key", "pcss", "V", name, 4), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(errorHas("9 are needed")) << ss_last_error();

    // One reference render written, then compared with itself: zero error, and the length of
    // the rows is named when the buffer is too small.
    fs::path dir = tempDir("compare");
    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    ss_scene* scene = smallScene(16, 12);
    ss_render_options o;
    ss_render_options_default(&o);
    o.samples = 4;
    ss_result* r = nullptr;
    ASSERT_EQ(ss_render(ctx, scene, 0, "reference", &o, &r), SS_OK);
    std::string exr = (dir / "a.exr").string();
    ASSERT_EQ(ss_write_exr(exr.c_str(), "ViewLayer", &r, 1), SS_OK);
    size_t length = 0;
    char tiny[8];
    EXPECT_EQ(ss_compare_exr(exr.c_str(), exr.c_str(), nullptr, nullptr, tiny, sizeof tiny, &length),
              SS_ERROR_INVALID_ARGUMENT);
    ASSERT_GT(length, sizeof tiny);
    std::string json(length, '\0');
    ASSERT_EQ(ss_compare_exr(exr.c_str(), exr.c_str(), nullptr, nullptr, json.data(), json.size(), &length), SS_OK);
    EXPECT_NE(json.find("\"rmse\":0,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"a\":\"Key_001_reference\""), std::string::npos) << json;
    EXPECT_EQ(ss_compare_exr((dir / "missing.exr").string().c_str(), nullptr, nullptr, nullptr, json.data(),
                             json.size(), &length),
              SS_ERROR_IO);
    EXPECT_TRUE(errorHas("missing.exr")) << ss_last_error();

    const float pixels[4] = {0.0f, 0.25f, 0.5f, 1.0f};
    std::string png = (dir / "v.png").string();
    EXPECT_EQ(ss_write_png_preview(png.c_str(), pixels, 2, 2), SS_OK);
    EXPECT_TRUE(fs::exists(png));
    EXPECT_EQ(ss_write_png_preview(png.c_str(), pixels, 0, 2), SS_ERROR_INVALID_ARGUMENT);
    ss_result_destroy(r);
    ss_scene_destroy(scene);
    ss_context_destroy(ctx);
    fs::remove_all(dir);
}

}  // namespace
