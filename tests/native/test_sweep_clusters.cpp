// Does `sweep` split a light into convex clusters and merge their shadows without interpolation
// (V = sum_k w_k V_k) so that a split rectangle agrees with the whole one, in the camera pass,
// the CPU lookup and the C API's shadow mesh?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "capi/capi_internal.h"
#include "core/error.h"
#include "io/metrics.h"
#include "methods/sweep/shadow.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::layer;
using test::run;

// The shared box over the ground, lit by a 2 x 1 rectangle 4 up (long side along x).
Scene rectangleBoxScene() {
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(test::makeBox({-0.6f, -0.6f, 0.8f}, {0.6f, 0.6f, 1.2f}, SS_MESH_CAST));
    Light l = test::makeDiskLight({0.0f, 0.0f, 4.0f}, 1.0f, "Rect");
    l.type = LightType::Rectangle;
    l.size = 2.0f;
    l.sizeY = 1.0f;
    s.addLight(l);
    s.setCamera(test::makeTopCamera());
    return s;
}

TEST(SweepClusters, SplitLightTilesTheRectangle) {
    Scene scene = rectangleBoxScene();
    const Light& light = scene.lights()[0];
    std::vector<LightCluster> parts = splitLight(light, 4);
    ASSERT_EQ(parts.size(), 4u);
    double weights = 0;
    for (size_t k = 0; k < parts.size(); ++k) {
        const Light& p = parts[k].light;
        weights += parts[k].weight;
        // Strips 0.5 x 1 along x, centres at x = -0.75, -0.25, 0.25, 0.75 (float exact).
        EXPECT_FLOAT_EQ(p.size, 0.5f);
        EXPECT_FLOAT_EQ(p.sizeY, 1.0f);
        EXPECT_FLOAT_EQ(p.position().x, -0.75f + 0.5f * float(k));
        EXPECT_FLOAT_EQ(p.position().y, 0.0f);
        EXPECT_FLOAT_EQ(p.position().z, 4.0f);
        EXPECT_EQ(p.direction(), light.direction());
    }
    EXPECT_NEAR(weights, 1.0, 1e-12);
    // A square is cut into rectangles; one cluster is the light itself.
    Light sq = light;
    sq.type = LightType::Square;
    std::vector<LightCluster> halves = splitLight(sq, 2);
    EXPECT_FLOAT_EQ(halves[0].light.size, 1.0f);
    EXPECT_FLOAT_EQ(halves[0].light.sizeY, 2.0f);
    EXPECT_EQ(halves[0].light.type, LightType::Rectangle);
    EXPECT_EQ(splitLight(light, 1)[0].light.size, light.size);
    // Round lights cannot be cut into convex strips of a uniform pattern here.
    Scene disk = test::sceneBox();
    try {
        splitLight(disk.lights()[0], 2);
        FAIL() << "a disk light was split";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_UNSUPPORTED);
        EXPECT_NE(std::string(e.what()).find("clusters"), std::string::npos);
    }
    RenderSettings bad;
    bad.options = {{"clusters", "0"}};
    EXPECT_THROW(sweepOptions(bad), Error);
    bad.options = {{"clusters", "2.5"}};
    EXPECT_THROW(sweepOptions(bad), Error);
}

// With fill=steps and equal weights each cluster's mesh integrates to (its samples' mean hard-shadow area); the
// merged mesh's weighted integral is then the mean over all samples, the same quantity the
// unsplit light gives. The box's shadow area moves by < 2 % over the light (top face 1.44
// scaled by (4/2.8)^2 = 2.94 for the centre; offsets of up to 1 in x move its sides, not its
// size, to first order), so split and unsplit agree within 1 %.
TEST(SweepClusters, CapiMeshIntegralMatchesUnsplit) {
    ss_scene* scene = nullptr;
    ASSERT_EQ(ss_scene_create(&scene), SS_OK);
    scene->scene = rectangleBoxScene();
    auto integral = [&](const char* settings, int32_t* used) {
        ss_render_options o;
        ss_render_options_default(&o);
        o.samples = 32;
        o.settings = settings;
        ss_sweep_mesh* mesh = nullptr;
        EXPECT_EQ(ss_sweep_shadow_mesh(scene, 0, &o, &mesh), SS_OK) << ss_last_error();
        const float *xyz = nullptr, *intensity = nullptr;
        const uint32_t* tris = nullptr;
        uint32_t nv = 0, nt = 0;
        ss_sweep_mesh_data(mesh, &xyz, &intensity, &nv, &tris, &nt);
        ss_sweep_mesh_info(mesh, nullptr, used);
        double sum = 0;
        for (uint32_t t = 0; t < nt; ++t) {
            const float* a = xyz + 3 * tris[3 * t];
            const float* b = xyz + 3 * tris[3 * t + 1];
            const float* c = xyz + 3 * tris[3 * t + 2];
            double area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
            EXPECT_GE(area, 0.0);
            sum += area * (intensity[tris[3 * t]] + intensity[tris[3 * t + 1]] + intensity[tris[3 * t + 2]]) / 3.0;
        }
        for (uint32_t i = 0; i < nv; ++i) {
            EXPECT_GE(intensity[i], 0.0f);
            EXPECT_LE(intensity[i], 1.0f);
        }
        ss_sweep_mesh_destroy(mesh);
        return sum;
    };
    int32_t used1 = 0, used4 = 0;
    double whole = integral("fill=steps;weights=equal", &used1);
    double split = integral("fill=steps;weights=equal;clusters=4", &used4);
    std::printf("mesh integral: whole %.4f, 4 clusters %.4f\n", whole, split);
    EXPECT_EQ(used1, 32);
    EXPECT_EQ(used4, 32);  // 8 per strip
    EXPECT_GT(whole, 2.85);
    EXPECT_LT(whole, 3.10);
    EXPECT_NEAR(split, whole, 0.01 * whole);
    ss_scene_destroy(scene);
}

// The camera pass: a rectangle split into 2 and 4 strips, each strip with its share of the 32
// samples, agrees with the whole light and with the reference. Measured (160x120): RMSE between
// split and whole 0.0115 (2) and 0.0112 (4), against reference 256 samples 0.0066 (whole),
// 0.0076 (2), 0.0093 (4). Bounds:
// split vs whole < 0.025 (two 32-sample estimates with different sample sets; the merge adds
// no interpolation error of its own), each against reference < 0.03 as in SweepQuality.
TEST(SweepClusters, SplitRectangleAgreesWithWholeLight) {
    Renderer renderer(SS_BACKEND_AUTO);
    Scene scene = rectangleBoxScene();
    const int refSamples = test::quickTests() ? 64 : 256;
    Layers ref = run(renderer, scene, "reference", refSamples);
    Layers whole = run(renderer, scene, "sweep", 32);
    const Image& mask = layer(whole, "mask");
    Metrics w = compareVisibility(layer(whole, "V"), layer(ref, "V"), &mask);
    std::printf("rectangle whole: %s\n", w.toString().c_str());
    EXPECT_LT(w.rmse, 0.03);
    for (const char* n : {"2", "4"}) {
        Layers split = run(renderer, scene, "sweep", 32, {{"clusters", n}});
        EXPECT_EQ(layer(split, "mask").pixels, mask.pixels);
        Metrics s = compareVisibility(layer(split, "V"), layer(whole, "V"), &mask);
        Metrics r = compareVisibility(layer(split, "V"), layer(ref, "V"), &mask);
        std::printf("rectangle clusters=%s vs whole: %s\n  vs reference: %s\n", n, s.toString().c_str(),
                    r.toString().c_str());
        EXPECT_GT(s.pixels, 10000u);
        EXPECT_LT(s.rmse, 0.025) << n;
        EXPECT_LT(r.rmse, 0.03) << n;
        EXPECT_GT(r.litIoU, 0.97) << n;
        for (float v : layer(split, "V").pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f);
        // The additive GL draw and the summed CPU lookups give the same picture (as in
        // SweepQuality.GlDrawMatchesCpuLookup: pixel centres on triangle sides may differ).
        Layers cpu = run(renderer, scene, "sweep", 32, {{"clusters", n}, {"raster", "cpu"}});
        const Image& a = layer(split, "V");
        const Image& b = layer(cpu, "V");
        double sum = 0;
        size_t off = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            double d = std::fabs(a.pixels[i] - b.pixels[i]);
            sum += d;
            off += d > 0.01;
        }
        EXPECT_LT(sum / a.pixels.size(), 1e-3) << n;
        EXPECT_LE(off, a.pixels.size() / 100) << n;
    }
}

}  // namespace
}  // namespace ss
