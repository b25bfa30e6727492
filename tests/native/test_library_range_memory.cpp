// Whether the reproducers of issue 29 (items 1-3) that live below the command hold through the
// C API: a mesh beyond the scene range is skipped and named while the rest keeps its shadows,
// nothing that far reaches the ray tracer, one far vertex does not spread the shadow maps, a
// light beyond the range gets a clear error, and a render past the memory budget is refused up
// front with the figures.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "softshadow/softshadow.h"

namespace {

void identity(float m[16]) {
    for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0f : 0.0f;
}

ss_light_desc diskLight(const char* name, glm::vec3 at) {
    ss_light_desc d{};
    d.name = name;
    d.type = SS_LIGHT_DISK;
    identity(d.light_to_world);
    d.light_to_world[12] = at.x;
    d.light_to_world[13] = at.y;
    d.light_to_world[14] = at.z;
    d.size = d.size_y = 1.0f;
    d.cast_shadows = 1;
    return d;
}

// A box over a ground plane lit from (3, 0, 4), seen from above with a far clip of 100: the
// scene range is 10000 x the far plane's farthest corner, about 1.1e6 from the camera.
// `extraBoxVertex`: the box gets one more vertex there that no triangle uses (a stray vertex in
// an otherwise fine mesh, as a modelling slip leaves one).
struct Scene {
    ss_scene* s = nullptr;
    explicit Scene(int w, int h, const glm::vec3* extraBoxVertex = nullptr) {
        EXPECT_EQ(ss_scene_create(&s), SS_OK);
        const float ground[12] = {-4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0};
        const uint32_t groundFaces[6] = {0, 1, 2, 0, 2, 3};
        EXPECT_EQ(ss_scene_add_mesh(s, "Ground", ground, 4, groundFaces, 2, nullptr, SS_MESH_CAST | SS_MESH_RECEIVE, nullptr),
                  SS_OK);
        std::vector<float> box;
        for (int i = 0; i < 8; ++i) {
            box.push_back((i & 1) ? 0.5f : -0.5f);
            box.push_back((i & 2) ? 0.5f : -0.5f);
            box.push_back((i & 4) ? 1.5f : 1.0f);
        }
        std::vector<uint32_t> faces = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                       2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
        if (extraBoxVertex) {
            box.insert(box.end(), {extraBoxVertex->x, extraBoxVertex->y, extraBoxVertex->z});
        }
        EXPECT_EQ(ss_scene_add_mesh(s, "Box", box.data(), uint32_t(box.size() / 3), faces.data(),
                                    uint32_t(faces.size() / 3), nullptr, SS_MESH_CAST | SS_MESH_RECEIVE, nullptr),
                  SS_OK);
        ss_light_desc light = diskLight("Key", {3.0f, 0.0f, 4.0f});
        EXPECT_EQ(ss_scene_add_light(s, &light, nullptr), SS_OK);
        ss_camera_desc cam{};
        glm::mat4 view = glm::lookAt(glm::vec3(0, -0.01f, 8), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
        glm::mat4 proj = glm::perspective(glm::radians(50.0f), float(w) / float(h), 0.1f, 100.0f);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                cam.world_to_camera[c * 4 + r] = view[c][r], cam.projection[c * 4 + r] = proj[c][r];
        cam.width = w;
        cam.height = h;
        cam.pixel_aspect = 1.0f;
        EXPECT_EQ(ss_scene_set_camera(s, &cam), SS_OK);
    }
    ~Scene() { ss_scene_destroy(s); }
    void addTet(const char* name, float farCoordinate) {
        const float tet[12] = {-3, 3, 0.2f, -2.5f, 3, 0.2f, -3, 3.5f, 0.2f, farCoordinate, 3, 0.7f};
        const uint32_t faces[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
        ASSERT_EQ(ss_scene_add_mesh(s, name, tet, 4, faces, 4, nullptr, SS_MESH_CAST | SS_MESH_RECEIVE, nullptr), SS_OK);
    }
};

struct Rendered {
    ss_status status = SS_ERROR_INTERNAL;
    std::string error, warnings, method;
    std::vector<float> v;
    double mean = NAN;
};

Rendered render(ss_context* ctx, ss_scene* scene, int light, const char* method, const char* settings = nullptr) {
    ss_render_options o;
    ss_render_options_default(&o);
    o.extra_layers = 0;
    o.settings = settings;
    ss_result* r = nullptr;
    Rendered out;
    out.status = ss_render(ctx, scene, light, method, &o, &r);
    if (out.status != SS_OK) {
        out.error = ss_last_error();
        return out;
    }
    out.warnings = ss_result_warnings(r);
    out.method = ss_result_method(r);
    const float* px = nullptr;
    int32_t w = 0, h = 0;
    EXPECT_EQ(ss_result_layer(r, 0, nullptr, &px, &w, &h), SS_OK);
    out.v.assign(px, px + size_t(w) * size_t(h));
    double sum = 0.0;
    for (float x : out.v) sum += x;
    out.mean = sum / double(out.v.size());
    ss_result_destroy(r);
    return out;
}

struct Context {
    ss_context* c = nullptr;
    Context() { EXPECT_EQ(ss_context_create(SS_BACKEND_AUTO, &c), SS_OK) << ss_last_error(); }
    ~Context() { ss_context_destroy(c); }
};

bool has(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

// 1. One vertex at 1e30 (or an object scaled 1e30) aborted in Embree (ray.valid()) with the
// reference and auto: the mesh is now skipped, named in the result's warnings, and the rest of
// the scene renders exactly as it does without it.
TEST(LibraryRangeMemory, MeshBeyondTheSceneRangeIsSkippedAndNamed) {
    Context ctx;
    Scene clean(48, 36), far(48, 36), scaled(48, 36);
    far.addTet("Far", 1e30f);
    scaled.addTet("Scaled", -2.0f);
    float huge[16];
    identity(huge);
    huge[0] = huge[5] = huge[10] = 1e30f;
    ASSERT_EQ(ss_scene_set_mesh_transform(scaled.s, 2, huge), SS_OK);
    const Rendered truth = render(ctx.c, clean.s, 0, "reference");
    ASSERT_EQ(truth.status, SS_OK) << truth.error;
    EXPECT_EQ(truth.warnings, "");
    EXPECT_LT(truth.mean, 0.99);  // the box's shadow is in view
    for (const char* method : {"reference", "auto", "shadow_map"}) {
        for (auto [scene, name] : {std::pair{&far, "Far"}, std::pair{&scaled, "Scaled"}}) {
            const Rendered r = render(ctx.c, scene->s, 0, method);
            ASSERT_EQ(r.status, SS_OK) << method << " " << name << ": " << r.error;
            EXPECT_TRUE(has(r.warnings, std::string("mesh '") + name + "' skipped")) << r.warnings;
            EXPECT_TRUE(has(r.warnings, "beyond the scene range")) << r.warnings;
            EXPECT_EQ(std::count(r.warnings.begin(), r.warnings.end(), '\n'), 1) << r.warnings;
            if (std::string(method) == "reference") {
                EXPECT_EQ(r.v, truth.v) << name;
            } else {
                EXPECT_NEAR(r.mean, truth.mean, 0.03) << method << " " << name;
            }
        }
    }
}

// 2. One stray vertex far out (inside the range) spread every shadow map over its own extent:
// shadow_map and dbuffer were lit everywhere (mean 1.000 where the truth is lower), and it
// lifted the reference's shadow rays off their surfaces by a millionth of its distance.
TEST(LibraryRangeMemory, OneFarVertexDoesNotSpreadTheShadowMaps) {
    Context ctx;
    const glm::vec3 stray(2e5f, 1e5f, 3e4f);
    Scene scene(64, 48, &stray);
    Scene clean(64, 48);
    const Rendered truth = render(ctx.c, clean.s, 0, "reference");
    ASSERT_EQ(truth.status, SS_OK) << truth.error;
    EXPECT_LT(truth.mean, 0.97);
    const Rendered traced = render(ctx.c, scene.s, 0, "reference");
    ASSERT_EQ(traced.status, SS_OK) << traced.error;
    EXPECT_EQ(traced.warnings, "");  // inside the range: nothing skipped
    EXPECT_EQ(traced.v, truth.v);    // a vertex no triangle uses changes nothing
    for (const char* method : {"shadow_map", "dbuffer", "pcss", "auto"}) {
        const Rendered r = render(ctx.c, scene.s, 0, method);
        ASSERT_EQ(r.status, SS_OK) << method << ": " << r.error;
        EXPECT_NEAR(r.mean, truth.mean, 0.02) << method << " (ran " << r.method << ")";
        double err = 0.0;
        for (size_t i = 0; i < r.v.size(); ++i) err += (r.v[i] - truth.v[i]) * (r.v[i] - truth.v[i]);
        EXPECT_LT(std::sqrt(err / double(r.v.size())), 0.15) << method;
    }
    // Past the range (1e10) the Box mesh goes, with a warning; the ground still renders.
    const glm::vec3 farther(1e10f, 0.0f, 0.0f);
    Scene beyond(64, 48, &farther);
    const Rendered skipped = render(ctx.c, beyond.s, 0, "auto");
    ASSERT_EQ(skipped.status, SS_OK) << skipped.error;
    EXPECT_TRUE(has(skipped.warnings, "mesh 'Box' skipped: its vertex 8")) << skipped.warnings;
}

// 2b. A light at 1e30 gave a pass lit everywhere and no word: it is refused, named; the scene's
// other lights render.
TEST(LibraryRangeMemory, LightBeyondTheSceneRangeIsRefusedByName) {
    Context ctx;
    Scene scene(32, 24);
    ss_light_desc far = diskLight("Faraway", {1e30f, 0.0f, 4.0f});
    int32_t index = -1;
    ASSERT_EQ(ss_scene_add_light(scene.s, &far, &index), SS_OK);
    for (const char* method : {"reference", "auto", "shadow_map"}) {
        const Rendered r = render(ctx.c, scene.s, index, method);
        EXPECT_EQ(r.status, SS_ERROR_INVALID_SCENE) << method;
        EXPECT_TRUE(has(r.error, "light 'Faraway' is 1e+30 from the camera, beyond the scene range")) << r.error;
    }
    EXPECT_EQ(render(ctx.c, scene.s, 0, "shadow_map").status, SS_OK);
}

// 3. Memory went far past the documented budget at 8192²: the budget is now worked out before
// any work, and a render past the limit is refused with both figures.
TEST(LibraryRangeMemory, RenderPastTheMemoryLimitIsRefusedUpFront) {
    Context ctx;
    Scene scene(1024, 1024);
    for (const char* method : {"shadow_map", "auto", "reference"}) {
        const Rendered r = render(ctx.c, scene.s, 0, method, "memory_limit_mb=200");
        EXPECT_EQ(r.status, SS_ERROR_INVALID_ARGUMENT) << method;
        EXPECT_TRUE(has(r.error, std::string(method) + " at 1024 x 1024 needs about")) << r.error;
        EXPECT_TRUE(has(r.error, "more than the memory limit 210 MB (the setting memory_limit_mb)")) << r.error;
        EXPECT_TRUE(has(r.error, "bytes a pixel")) << r.error;
    }
    const Rendered bad = render(ctx.c, scene.s, 0, "shadow_map", "memory_limit_mb=-5");
    EXPECT_EQ(bad.status, SS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(has(bad.error, "memory_limit_mb")) << bad.error;
}

}  // namespace
