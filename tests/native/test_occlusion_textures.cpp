// Checks occlusion_textures end to end: against the reference on the shared scenes and a foliage scene.
// SPDX-License-Identifier: GPL-3.0-or-later
// Better than shadow_map, the product combination, continuity across slice planes, and the
// thin-occluder leak fix.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "io/metrics.h"
#include "methods/method.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::layer;
using test::run;

int referenceSamples() { return test::quickTests() ? 64 : 256; }

Renderer& renderer() {
    static Renderer r(SS_BACKEND_AUTO);
    return r;
}

// A closed thin box between two corners: occluders here are solid plates.
Mesh plate(const glm::vec3& lo, const glm::vec3& hi) { return test::makeBox(lo, hi, SS_MESH_CAST); }

// Leaves: small two-sided quads at random heights and tilts in a crown above the ground
// (an open mesh of many small pieces, like foliage).
Mesh foliage(int leaves, uint32_t seed, uint32_t flags) {
    Mesh m;
    m.name = "foliage";
    m.flags = flags;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), h(1.2f, 2.6f), size(0.08f, 0.2f), angle(0.0f, 6.2831853f);
    for (int i = 0; i < leaves; ++i) {
        glm::vec3 c(1.3f * u(rng), 1.3f * u(rng), h(rng));
        if (glm::length(glm::vec2(c)) > 1.3f) continue;
        float s = size(rng);
        glm::mat4 r = glm::rotate(glm::mat4(1.0f), angle(rng), glm::normalize(glm::vec3(u(rng), u(rng), 0.3f + std::abs(u(rng)))));
        glm::vec3 ax = glm::vec3(r * glm::vec4(s, 0, 0, 0)), ay = glm::vec3(r * glm::vec4(0, s, 0, 0));
        uint32_t base = uint32_t(m.objectPositions.size());
        m.objectPositions.push_back(c - ax - ay);
        m.objectPositions.push_back(c + ax - ay);
        m.objectPositions.push_back(c + ax + ay);
        m.objectPositions.push_back(c - ax + ay);
        m.triangles.push_back({base, base + 1, base + 2});
        m.triangles.push_back({base, base + 2, base + 3});
    }
    m.finalize();
    return m;
}

Scene sceneFoliage(uint32_t leafFlags) {
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(foliage(260, 17, leafFlags));
    s.addLight(test::makeDiskLight({0.0f, 0.0f, 4.0f}, 1.5f));
    s.setCamera(test::makeTopCamera());
    return s;
}

TEST(OcclusionTextures, SaneLayersAndEveryFilterRuns) {
    Scene scene = test::sceneBox();
    for (const char* filter : {"nbuffer", "sat", "mipmap"}) {
        Layers l = run(renderer(), scene, "occlusion_textures", 0, {{"filter", filter}});
        for (const char* name : {"V", "mask", "umbra", "penumbra", "slice_0", "slice_7"})
            ASSERT_NE(l.find(name), nullptr) << filter << ": no layer " << name;
        const Image& V = layer(l, "V");
        const Image& mask = layer(l, "mask");
        size_t bad = 0, umbra = 0;
        for (size_t i = 0; i < V.pixels.size(); ++i) {
            float v = V.pixels[i];
            if (!std::isfinite(v) || v < 0.0f || v > 1.0f || (mask.pixels[i] < 0.5f && v != 1.0f)) ++bad;
            umbra += layer(l, "umbra").pixels[i] > 0.5f;
        }
        EXPECT_EQ(bad, 0u) << filter;
        EXPECT_GT(umbra, 40u) << filter << ": the box must cast an umbra";
    }
}

// A first pass leaves out the pixels no slice can shadow (with every filter), and with the SAT
// the shading loop reads only the slices whose occupied texels the kernel can reach; any other
// slice's box filters to exactly 0, so leaving it out must change no pixel (slice layers
// included), on a scene where most slices are empty at most pixels and the ground fills the
// last slice.
TEST(OcclusionTextures, SkippingEmptySlicesChangesNothing) {
    Scene scene = sceneFoliage(SS_MESH_CAST | SS_MESH_THIN);
    // N-Buffers and mipmaps with 4 slices: their 16-slice programs take llvmpipe ~15 s to build.
    for (auto [filter, fade, slices] : {std::tuple{"sat", "below", "16"}, {"sat", "paper", "16"},
                                        {"nbuffer", "below", "4"}, {"mipmap", "below", "4"}}) {
        SCOPED_TRACE(std::string(filter) + ", fade " + fade);
        std::map<std::string, std::string> options = {{"slices", slices}, {"fade", fade}, {"filter", filter}};
        Layers skipping = run(renderer(), scene, "occlusion_textures", 0, options);
        options["debug.skip_empty_slices"] = "0";
        Layers reading = run(renderer(), scene, "occlusion_textures", 0, options);
        for (const char* name : {"V", "mask", "slice_0", "slice_3"}) {
            const Image& a = layer(skipping, name);
            const Image& b = layer(reading, name);
            size_t differ = 0;
            for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
            EXPECT_EQ(differ, 0u) << name;
        }
        size_t shaded = 0;
        for (float v : layer(skipping, "V").pixels) shaded += v < 0.99f;
        EXPECT_GT(shaded, 500u) << "the leaves must cast shadows for the comparison to mean anything";
    }
}

// Quality bounds, measured at 160 x 120 against 256 reference samples (noise ~0.02 RMS) and
// stated with a margin; the method is an approximation (slices, equal-area box kernel, no
// cosine weighting). Measured (defaults: sat, 8 slices of 512): RMSE box 0.023, concave 0.032,
// overlapping 0.021, torus 0.046, foliage 0.158; umbra IoU 0.49-0.64; lit IoU >= 0.993
// (foliage 0.82); shadow_map 0.06-0.08 (foliage 0.30). Under SS_TEST_QUICK the reference
// has 64 samples: its noise (~0.03 RMS in the penumbra) still fits under these bounds.
TEST(OcclusionTextures, CloseToReferenceAndBetterThanShadowMap) {
    std::vector<test::NamedScene> scenes = test::sharedScenes();
    scenes.push_back({"foliage", sceneFoliage(SS_MESH_CAST | SS_MESH_THIN)});
    for (auto& [name, scene] : scenes) {
        Layers ref = run(renderer(), scene, "reference", referenceSamples());
        Layers ot = run(renderer(), scene, "occlusion_textures");
        Layers sm = run(renderer(), scene, "shadow_map");
        const Image* mask = &layer(ref, "mask");
        Metrics m = compareVisibility(layer(ot, "V"), layer(ref, "V"), mask);
        Metrics h = compareVisibility(layer(sm, "V"), layer(ref, "V"), mask);
        std::printf("%-12s occlusion_textures %s\n%-12s shadow_map         %s\n", name.c_str(), m.toString().c_str(),
                    name.c_str(), h.toString().c_str());
        bool leaves = name == "foliage";
        EXPECT_LT(m.rmse, leaves ? 0.20 : 0.07) << name;
        EXPECT_LT(m.rmse, 0.75 * h.rmse) << name << ": must beat the hard shadow clearly";
        EXPECT_GT(m.litIoU, leaves ? 0.75 : 0.97) << name;
        EXPECT_GT(m.litIoU, h.litIoU) << name;
        if (!leaves) {
            EXPECT_GT(m.umbraIoU, 0.4) << name;
            EXPECT_GT(m.umbraIoU, h.umbraIoU) << name;
        }
    }
}

// Two plates, at different heights, each hide one half of a square light from the ground point
// under the light: each slice's shadow there is 1/2, so the product gives 1/4, while the sum
// would give 0 and the maximum 1/2 (the truth is 0: the halves are disjoint).
TEST(OcclusionTextures, ProductCombinationOfTwoHalfBlockingSlices) {
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    // Light square of side 1 at height 4. From P = (0, 0, 0), the plate at height h blocks
    // rays to light points with x > 0 when it covers x in [0, 0.5 h / 4] (and y likewise).
    // The plates stop short in y (the light's footprint is |y| <= h / 8) so the camera, looking
    // from y = -2.5, still sees P between them.
    s.addMesh(plate({0.0f, -0.2f, 1.00f}, {0.5f, 0.2f, 1.05f}));
    s.addMesh(plate({-0.8f, -0.4f, 2.50f}, {0.0f, 0.4f, 2.55f}));
    Light light = test::makeDiskLight({0.0f, 0.0f, 4.0f}, 1.0f, "Square");
    light.type = LightType::Square;
    s.addLight(light);
    s.setCamera(test::makeTopCamera());
    Layers l = run(renderer(), s, "occlusion_textures", 0, {{"filter", "sat"}});
    glm::vec2 px = s.camera().worldToPixel({0.0f, 0.0f, 0.0f});
    ASSERT_GT(layer(l, "mask").at(int(px.x), int(px.y)), 0.5f) << "the camera must see P";
    float v = layer(l, "V").at(int(px.x), int(px.y));
    std::printf("V under the two half plates: %.3f (product 0.25, sum 0, max 0.5)\n", v);
    // Each slice's filtered shadow is 1/2 up to the texel the plate edge falls in (a texel of
    // 512 over the frustum is ~1/20 of the kernel here): +-0.06 on the product.
    EXPECT_NEAR(v, 0.25f, 0.06f);
    EXPECT_GT(std::abs(v - 0.0f), 0.15f) << "must differ from the additive combination";
    EXPECT_GT(std::abs(v - 0.5f), 0.15f) << "must differ from the maximum";
}

// A ramp tilted through many slice planes under a box: V along the ramp must not jump where
// the receiver crosses a slice plane.
TEST(OcclusionTextures, NoJumpWhereAReceiverCrossesSlicePlanes) {
    Scene s;
    Mesh ramp;
    ramp.name = "ramp";
    ramp.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    ramp.objectPositions = {{-3, -3, 0.0f}, {3, -3, 1.5f}, {3, 3, 1.5f}, {-3, 3, 0.0f}};
    ramp.triangles = {{0, 1, 2}, {0, 2, 3}};
    ramp.finalize();
    s.addMesh(std::move(ramp));
    s.addMesh(test::makeBox({-0.5f, -0.5f, 2.2f}, {0.5f, 0.5f, 2.5f}, SS_MESH_CAST));
    // A receiver hidden under the ramp keeps the ramp in the slices: a tilted plane with
    // everything on its lit side is left out of them (OcclusionTexturesTilted), and this test
    // is about receivers that are sliced with the casters.
    s.addMesh(test::makeBox({-0.1f, -0.1f, -1.0f}, {0.1f, 0.1f, -0.9f}, SS_MESH_RECEIVE));
    s.addLight(test::makeDiskLight({0.0f, 0.0f, 4.5f}, 1.5f));
    s.setCamera(test::makeTopCamera());
    Layers ot = run(renderer(), s, "occlusion_textures", 0, {{"slices", "16"}});
    Layers ref = run(renderer(), s, "reference", referenceSamples());
    auto largestJump = [](const Image& V, const Image& mask) {
        float worst = 0.0f;
        for (int y = 0; y < V.height; ++y)
            for (int x = 0; x + 1 < V.width; ++x)
                if (mask.at(x, y) > 0.5f && mask.at(x + 1, y) > 0.5f)
                    worst = std::max(worst, std::abs(V.at(x + 1, y) - V.at(x, y)));
        return worst;
    };
    float jump = largestJump(layer(ot, "V"), layer(ot, "mask"));
    float refJump = largestJump(layer(ref, "V"), layer(ref, "mask"));
    std::printf("largest neighbour jump in V: occlusion_textures %.3f, reference %.3f\n", jump, refJump);
    // The true penumbra changes by up to refJump between neighbours, plus sampling noise; a
    // seam at a slice plane would jump by a slice's whole share (>= 0.3 here). Bound: 0.2.
    EXPECT_LT(jump, 0.2f);
    Metrics m = compareVisibility(layer(ot, "V"), layer(ref, "V"), &layer(ref, "mask"));
    EXPECT_LT(m.rmse, 0.12) << m.toString();
    // The paper's literal rule (fade the slice holding P) lets the ramp shadow itself wherever
    // it nears the bottom of a slice: the reason `below` is the default.
    Layers paper = run(renderer(), s, "occlusion_textures", 0, {{"slices", "16"}, {"fade", "paper"}});
    Metrics p = compareVisibility(layer(paper, "V"), layer(ref, "V"), &layer(ref, "mask"));
    std::printf("ramp RMSE: fade=below %.3f, fade=paper %.3f\n", m.rmse, p.rmse);
    EXPECT_GT(p.rmse, m.rmse + 0.05);
}

// A steep thin plane (one open quad) over the ground: its slices' strips do not line up when
// seen from the ground, so light leaks through without the fix; filling the next slice closes it.
TEST(OcclusionTextures, ThinOccluderLeakFix) {
    auto make = [](uint32_t flags) {
        Scene s;
        s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
        Mesh wall;
        wall.name = "thin";
        wall.flags = flags;
        // Tilted 70 degrees from the ground, spanning heights 0.8 .. 2.6.
        wall.objectPositions = {{-1.2f, -0.35f, 0.8f}, {1.2f, -0.35f, 0.8f}, {1.2f, 0.3f, 2.6f}, {-1.2f, 0.3f, 2.6f}};
        wall.triangles = {{0, 1, 2}, {0, 2, 3}};
        wall.finalize();
        s.addMesh(std::move(wall));
        s.addLight(test::makeDiskLight({0.0f, 0.0f, 4.0f}, 0.6f));
        s.setCamera(test::makeTopCamera());
        return s;
    };
    Scene plain = make(SS_MESH_CAST), thin = make(SS_MESH_CAST | SS_MESH_THIN);
    Layers ref = run(renderer(), plain, "reference", referenceSamples());
    Layers leaky = run(renderer(), plain, "occlusion_textures", 0, {{"slices", "16"}});
    Layers fixedL = run(renderer(), thin, "occlusion_textures", 0, {{"slices", "16"}});
    Layers forced = run(renderer(), plain, "occlusion_textures", 0, {{"slices", "16"}, {"thin_fix", "on"}});
    // Mean V over the reference umbra: light that reaches where none should.
    auto leak = [&](const Layers& l) {
        const Image& r = layer(ref, "V");
        const Image& V = layer(l, "V");
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < r.pixels.size(); ++i)
            if (layer(ref, "mask").pixels[i] > 0.5f && r.pixels[i] < kUmbraThreshold) sum += V.pixels[i], ++n;
        return n ? sum / double(n) : 1.0;
    };
    double without = leak(leaky), with = leak(fixedL), viaSetting = leak(forced);
    std::printf("mean V in the reference umbra: without fix %.3f, SS_MESH_THIN %.3f, thin_fix=on %.3f\n", without,
                with, viaSetting);
    EXPECT_GT(without, 0.15) << "the thin plane should leak without the fix";
    EXPECT_LT(with, 0.08) << "the fix should close the leaks";
    EXPECT_NEAR(with, viaSetting, 1e-6);
}

}  // namespace
}  // namespace ss
