// Does the C API hand out the sweep shadow mesh: world-space vertices on the receiver with
// intensities in [0, 1], whose intensity integral is the box's mean hard-shadow area?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "capi/capi_internal.h"
#include "core/memory_budget.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace {

ss_scene* capiScene(ss::Scene s) {
    ss_scene* scene = nullptr;
    EXPECT_EQ(ss_scene_create(&scene), SS_OK);
    scene->scene = std::move(s);
    return scene;
}

ss_render_options optionsWith(int samples) {
    ss_render_options o;
    ss_render_options_default(&o);
    o.samples = samples;
    return o;
}

}  // namespace

TEST(SweepCapi, ShadowMeshOfTheBox) {
    ss_scene* scene = capiScene(ss::test::sceneBox());
    ss_render_options o = optionsWith(16);
    // Equal weights: the integral is then the samples' mean hard-shadow area (irradiance
    // weights, the default, make it the weighted mean; see test_sweep_weights.cpp).
    o.settings = "fill=steps;weights=equal";
    ss_sweep_mesh* mesh = nullptr;
    ASSERT_EQ(ss_sweep_shadow_mesh(scene, 0, &o, &mesh), SS_OK) << ss_last_error();
    const float *xyz = nullptr, *intensity = nullptr;
    const uint32_t* tris = nullptr;
    uint32_t nv = 0, nt = 0;
    ASSERT_EQ(ss_sweep_mesh_data(mesh, &xyz, &intensity, &nv, &tris, &nt), SS_OK);
    int32_t receiver = -1, used = 0;
    ASSERT_EQ(ss_sweep_mesh_info(mesh, &receiver, &used), SS_OK);
    EXPECT_EQ(used, 16);
    EXPECT_TRUE(scene->scene.meshes()[receiver].receives());
    ASSERT_GT(nt, 0u);
    double integral = 0;
    for (uint32_t i = 0; i < nv; ++i) {
        EXPECT_NEAR(xyz[3 * i + 2], 0.0f, 1e-5f);  // on the ground plane z = 0
        EXPECT_GE(intensity[i], 0.0f);
        EXPECT_LE(intensity[i], 1.0f);
    }
    for (uint32_t t = 0; t < nt; ++t) {
        const float* a = xyz + 3 * tris[3 * t];
        const float* b = xyz + 3 * tris[3 * t + 1];
        const float* c = xyz + 3 * tris[3 * t + 2];
        double area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        EXPECT_GE(area, 0.0);  // counter-clockwise seen from above (the light's side)
        integral += area * (intensity[tris[3 * t]] + intensity[tris[3 * t + 1]] + intensity[tris[3 * t + 2]]) / 3.0;
    }
    // Box 1.2 wide, top at 1.2, light 4 up: the centre's hard shadow is the top face scaled by
    // 4 / 2.8, area 2.94; offset samples stick out by < 0.03 world units on a side: < 3.1.
    EXPECT_GT(integral, 2.90);
    EXPECT_LT(integral, 3.10);
    ss_sweep_mesh_destroy(mesh);
    EXPECT_NE(ss_sweep_shadow_mesh(scene, 7, &o, &mesh), SS_OK);
    EXPECT_NE(std::string(ss_last_error()).find("light index"), std::string::npos);
    // The same settings reader as ss_render: a key the sweep does not read is refused by name.
    o.settings = "boarder=0.5";
    EXPECT_EQ(ss_sweep_shadow_mesh(scene, 0, &o, &mesh), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ss_last_error()).find("no setting 'boarder'"), std::string::npos) << ss_last_error();
    ss_scene_destroy(scene);
}

// The shadow mesh grows with the samples (its irradiance weights by samples x triangles): one
// past the memory limit is refused with its figure once its triangles are known, and the same
// mesh without weights, under the limit, is made.
TEST(SweepCapi, ShadowMeshPastTheMemoryLimitIsRefused) {
    ss_scene* scene = capiScene(ss::test::sceneTorus());
    ss_render_options o = optionsWith(32);
    ss_sweep_mesh* mesh = nullptr;
    ASSERT_EQ(ss_sweep_shadow_mesh(scene, 0, &o, &mesh), SS_OK) << ss_last_error();
    uint32_t nv = 0, nt = 0;
    int32_t receiver = -1, used = 0;
    ASSERT_EQ(ss_sweep_mesh_data(mesh, nullptr, nullptr, &nv, nullptr, &nt), SS_OK);
    ASSERT_EQ(ss_sweep_mesh_info(mesh, &receiver, &used), SS_OK);
    ss_sweep_mesh_destroy(mesh);
    ASSERT_GT(nt, 1000u);
    ASSERT_EQ(used, 32);
    const double weighed = double(nt) * (ss::kBudgetBytesPerSweepTriangle + ss::kBudgetBytesPerSweepWeight * (used + 1));
    const double plain = double(nt) * ss::kBudgetBytesPerSweepTriangle;
    const int limitMib = int((weighed + plain) / 2.0 / double(1 << 20));
    ASSERT_GT(double(limitMib) * (1 << 20), plain);
    ASSERT_LT(double(limitMib) * (1 << 20), weighed);
    const std::string limit = "memory_limit_mb=" + std::to_string(limitMib);
    o.settings = limit.c_str();
    mesh = nullptr;
    EXPECT_EQ(ss_sweep_shadow_mesh(scene, 0, &o, &mesh), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(mesh, nullptr);
    const std::string error = ss_last_error();
    const std::string light = scene->scene.light(0).name;
    EXPECT_NE(error.find("light '" + light + "': sweep's shadow mesh of " + std::to_string(nt) +
                         " triangles from 32 light samples needs about " + ss::bytesText(weighed)),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("more than the memory limit " + ss::bytesText(double(limitMib) * (1 << 20)) +
                         " (the setting memory_limit_mb): use fewer samples, or weights=equal"),
              std::string::npos)
        << error;
    const std::string equal = limit + ";weights=equal";
    o.settings = equal.c_str();
    ASSERT_EQ(ss_sweep_shadow_mesh(scene, 0, &o, &mesh), SS_OK) << ss_last_error();
    ASSERT_EQ(ss_sweep_mesh_data(mesh, nullptr, nullptr, &nv, nullptr, &nt), SS_OK);
    EXPECT_GT(nt, 1000u);
    ss_sweep_mesh_destroy(mesh);
    ss_scene_destroy(scene);
}
