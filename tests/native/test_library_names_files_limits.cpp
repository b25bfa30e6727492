// Whether the reproducers of issue 29 that reach the library through the C API (the add-on's
// way in) get a clear refusal before anything renders, and whether renders stop when asked.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <string>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "softshadow/softshadow.h"

namespace {

bool errorHas(const std::string& fragment) { return std::string(ss_last_error()).find(fragment) != std::string::npos; }

ss_light_desc disk(const char* name, float x) {
    ss_light_desc light{};
    light.name = name;
    light.type = SS_LIGHT_DISK;
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0, 4));
    std::memcpy(light.light_to_world, &m[0][0], sizeof light.light_to_world);
    light.size = 0.5f;
    light.cast_shadows = 1;
    return light;
}

ss_camera_desc camera(int w, int h) {
    ss_camera_desc cam{};
    glm::mat4 view = glm::lookAt(glm::vec3(0, -0.01f, 8), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
    glm::mat4 proj = glm::perspective(glm::radians(50.0f), float(w) / float(h), 0.1f, 100.0f);
    std::memcpy(cam.world_to_camera, &view[0][0], sizeof cam.world_to_camera);
    std::memcpy(cam.projection, &proj[0][0], sizeof cam.projection);
    cam.width = w;
    cam.height = h;
    cam.pixel_aspect = 1.0f;
    return cam;
}

ss_scene* plateOverGround(int w, int h) {
    ss_scene* s = nullptr;
    EXPECT_EQ(ss_scene_create(&s), SS_OK);
    const float ground[12] = {-4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0};
    const float plate[12] = {-1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1};
    const uint32_t faces[6] = {0, 1, 2, 0, 2, 3};
    EXPECT_EQ(ss_scene_add_mesh(s, "Ground", ground, 4, faces, 2, nullptr, SS_MESH_CAST | SS_MESH_RECEIVE, nullptr), SS_OK);
    EXPECT_EQ(ss_scene_add_mesh(s, "Plate", plate, 4, faces, 2, nullptr, SS_MESH_CAST | SS_MESH_RECEIVE, nullptr), SS_OK);
    ss_light_desc key = disk("Key", 0.0f);
    EXPECT_EQ(ss_scene_add_light(s, &key, nullptr), SS_OK);
    ss_camera_desc cam = camera(w, h);
    EXPECT_EQ(ss_scene_set_camera(s, &cam), SS_OK);
    return s;
}

// 4. Two lights whose names make the same pass name: refused when the second is added, naming
// both, not when the EXR is written after every light rendered.
TEST(LibraryNamesFilesLimits, LightsWithTheSamePassNameAreRefusedNamingBoth) {
    ss_scene* s = plateOverGround(16, 12);
    ss_light_desc dotted = disk("A.B", 1.0f), spaced = disk("A B", 1.0f), underscored = disk("A_B", -1.0f);
    ASSERT_EQ(ss_scene_add_light(s, &dotted, nullptr), SS_OK);
    EXPECT_EQ(ss_scene_add_light(s, &underscored, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(errorHas("'A.B'") && errorHas("'A_B'") && errorHas("same passes") && errorHas("A_B_<method>"))
        << ss_last_error();
    EXPECT_EQ(ss_scene_add_light(s, &spaced, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(errorHas("'A.B'") && errorHas("'A B'")) << ss_last_error();
    EXPECT_EQ(ss_scene_light_count(s), 2);
    // Renaming a light into a collision is refused too; renaming it in place is not.
    EXPECT_EQ(ss_scene_update_light(s, 0, &underscored), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(errorHas("'A.B'") && errorHas("'A_B'")) << ss_last_error();
    ss_light_desc renamed = disk("A_B", 1.0f);
    EXPECT_EQ(ss_scene_update_light(s, 1, &renamed), SS_OK) << ss_last_error();
    EXPECT_STREQ(ss_scene_light_name(s, 1), "A_B");
    ss_scene_destroy(s);
}

// 10. Control and bidirectional formatting characters in names, as docs/scene-format.md says.
TEST(LibraryNamesFilesLimits, ControlAndBidiCharactersInNamesAreRefused) {
    ss_scene* s = plateOverGround(16, 12);
    const char* refused[] = {"csi\xC2\x9B" "2J", "rtl\xE2\x80\xAE" "txt.exr", "isolate\xE2\x81\xA6", "mark\xE2\x80\x8F",
                             "del\x7F", "nel\xC2\x85"};
    for (const char* name : refused) {
        ss_light_desc light = disk(name, 2.0f);
        EXPECT_EQ(ss_scene_add_light(s, &light, nullptr), SS_ERROR_INVALID_SCENE) << name;
        EXPECT_TRUE(errorHas("a bidirectional formatting character")) << ss_last_error();
        // The message shows the character escaped, never raw.
        EXPECT_EQ(std::string(ss_last_error()).find(name), std::string::npos) << ss_last_error();
    }
    ss_light_desc rtl = disk("rtl\xE2\x80\xAE", 2.0f);
    EXPECT_EQ(ss_scene_add_light(s, &rtl, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(errorHas("\\u202E")) << ss_last_error();
    // Printable non-ASCII stays allowed: accents, CJK, emoji, and U+00A0.
    for (const char* name : {"Lumi\xC3\xA8re", "\xE5\x85\x89", "\xF0\x9F\x92\xA1", "nb\xC2\xA0sp"}) {
        ss_light_desc light = disk(name, 2.0f);
        EXPECT_EQ(ss_scene_add_light(s, &light, nullptr), SS_OK) << name << ": " << ss_last_error();
    }
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t face[3] = {0, 1, 2};
    EXPECT_EQ(ss_scene_add_mesh(s, "m\xE2\x80\xAE", tri, 3, face, 1, nullptr, SS_MESH_CAST, nullptr), SS_ERROR_INVALID_SCENE);
    EXPECT_EQ(ss_scene_set_view_layer(s, "V\xC2\x9B"), SS_ERROR_INVALID_ARGUMENT);
    ss_scene_destroy(s);
}

// 11. The side limit is the texture size every OpenGL 4.5 context has, checked when the camera
// is set (a 32768 x 4 camera used to fail in the middle of a render on the texture).
TEST(LibraryNamesFilesLimits, CameraSidesAreCheckedAgainstTheGuaranteedTextureSize) {
    ss_scene* s = plateOverGround(16, 12);
    ss_camera_desc wide = camera(32768, 4);
    EXPECT_EQ(ss_scene_set_camera(s, &wide), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(errorHas("32768x4") && errorHas("1..16384")) << ss_last_error();
    ss_camera_desc widest = camera(16384, 4);
    ASSERT_EQ(ss_scene_set_camera(s, &widest), SS_OK) << ss_last_error();
    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    char info[8192];
    ASSERT_EQ(ss_context_info(ctx, info, sizeof info), SS_OK);
    EXPECT_NE(std::string(info).find("max_texture_size"), std::string::npos);
    for (const char* method : {"shadow_map", "reference"}) {
        ss_result* r = nullptr;
        EXPECT_EQ(ss_render(ctx, s, 0, method, nullptr, &r), SS_OK) << method << ": " << ss_last_error();
        const char* name = nullptr;
        const float* pixels = nullptr;
        int32_t w = 0, h = 0;
        ASSERT_EQ(ss_result_layer(r, 0, &name, &pixels, &w, &h), SS_OK);
        EXPECT_EQ(w, 16384);
        EXPECT_EQ(h, 4);
        ss_result_destroy(r);
    }
    ss_context_destroy(ctx);
    ss_scene_destroy(s);
}

// 9. A render on the add-on's shared context stops when asked from another thread (a file load
// during F12), without the context being destroyed, and the next render runs as usual.
TEST(LibraryNamesFilesLimits, CancelRendersStopsTheRenderInFlightAndKeepsTheContext) {
    ss_context* ctx = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &ctx), SS_OK);
    ss_context_cancel_renders(ctx);  // nothing in flight: nothing to cancel later
    ss_scene* scene = plateOverGround(64, 48);
    std::atomic<bool> started{false};
    ss_render_options o;
    ss_render_options_default(&o);
    o.samples = 4096;  // seconds of tracing: still running when the cancel comes
    o.settings = "threads=1";
    o.progress_user = &started;
    o.progress = [](void* user, float, const char*) {
        static_cast<std::atomic<bool>*>(user)->store(true);
        return 0;  // never asks to stop itself: the flag alone must stop the render
    };
    ss_status status = SS_OK;
    std::chrono::steady_clock::time_point stopped;
    std::thread worker([&] {
        ss_result* r = nullptr;
        status = ss_render(ctx, scene, 0, "reference", &o, &r);
        stopped = std::chrono::steady_clock::now();
        ss_result_destroy(r);
    });
    while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    auto asked = std::chrono::steady_clock::now();
    ss_context_cancel_renders(ctx);
    worker.join();
    EXPECT_EQ(status, SS_ERROR_CANCELLED);
    EXPECT_LT(std::chrono::duration<double>(stopped - asked).count(), 1.0) << "not stopped within a second";
    ss_result* r = nullptr;
    o.samples = 16;
    EXPECT_EQ(ss_render(ctx, scene, 0, "reference", &o, &r), SS_OK) << ss_last_error();
    ss_result_destroy(r);
    ss_context_destroy(ctx);
    ss_scene_destroy(scene);
}

// 5. The temporary-file handlers go only where a signal still has its default action.
TEST(LibraryNamesFilesLimits, SignalHandlersKeepTheHostsOwn) {
    pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        signal(SIGINT, SIG_IGN);   // a host that ignores one
        signal(SIGHUP, [](int) {});  // and handles another
        int installed = ss_remove_temporary_files_on_signals();
        struct sigaction intAction {}, hupAction {}, termAction {};
        sigaction(SIGINT, nullptr, &intAction);
        sigaction(SIGHUP, nullptr, &hupAction);
        sigaction(SIGTERM, nullptr, &termAction);
        bool kept = intAction.sa_handler == SIG_IGN && hupAction.sa_handler != SIG_DFL &&
                    termAction.sa_handler != SIG_DFL && termAction.sa_handler != SIG_IGN;
        bool again = ss_remove_temporary_files_on_signals() == 1;
        _exit(installed == 1 && kept && again ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

}  // namespace
