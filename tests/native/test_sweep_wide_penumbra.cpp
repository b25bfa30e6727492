// Does `sweep` keep a wide penumbra free of bands? With one set of 16 samples the rings of a
// penumbra 50+ pixels wide lie unevenly (several rings in one pixel, then none for several), so
// the Gouraud ramp steps; the automatic passes average interleaved sample sets there.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "io/metrics.h"
#include "methods/sweep/shadow.h"
#include "renderer/renderer.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::layer;
using test::run;

// A 2 m plate 1.6-1.7 m over the ground under a 2 m light at 4 m, turned `yaw` about the
// vertical: the penumbra is about 1.5 m wide, 55 pixels at 320 x 240.
Scene widePenumbraScene(LightType type, float yaw) {
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(test::makeBox({-1.0f, -1.0f, 1.6f}, {1.0f, 1.0f, 1.7f}, SS_MESH_CAST));
    Light light = test::makeDiskLight({0.0f, 0.0f, 4.0f}, 2.0f, "Wide");
    light.type = type;
    light.lightToWorld = glm::rotate(light.lightToWorld, glm::radians(yaw), glm::vec3(0, 0, 1));
    s.addLight(light);
    s.setCamera(test::makeTopCamera(320, 240));
    return s;
}

Image both(const Image& a, const Image& b) {
    Image m(a.width, a.height, 0.0f);
    for (size_t i = 0; i < m.pixels.size(); ++i) m.pixels[i] = (a.pixels[i] > 0.5f && b.pixels[i] > 0.5f) ? 1.0f : 0.0f;
    return m;
}

// The 99th percentile of |V(p) - V(q)| over neighbouring pixels p, q (across and down) in the
// mask where the reference is in penumbra: a band is a run of pixels where the ramp falls
// several times faster than the truth's, so this grows with the banding, and the reference's
// own (its noise and its true slope) is the yardstick.
double neighbourStep(const Image& V, const Image& ref, const Image& mask) {
    std::vector<float> d;
    for (int y = 0; y + 1 < V.height; ++y)
        for (int x = 0; x + 1 < V.width; ++x)
            for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
                if (mask.at(x, y) < 0.5f || mask.at(x + dx, y + dy) < 0.5f) continue;
                float r0 = ref.at(x, y), r1 = ref.at(x + dx, y + dy);
                if (std::max(r0, r1) < 0.02f || std::min(r0, r1) > 0.98f) continue;
                d.push_back(std::abs(V.at(x + dx, y + dy) - V.at(x, y)));
            }
    if (d.empty()) return 0.0;
    std::sort(d.begin(), d.end());
    return d[size_t(0.99 * double(d.size() - 1))];
}

// Measured (reference 256 samples), p99 step one set / auto / reference
// and RMSE one set / auto: square 0.077 / 0.051 / 0.027, RMSE 0.025 / 0.010; square turned 30
// degrees 0.087 / 0.041 / 0.038, 0.021 / 0.011; disk 0.114 / 0.051 / 0.036, 0.024 / 0.012.
TEST(SweepWidePenumbra, AutomaticPassesEvenOutTheBands) {
    Renderer renderer(SS_BACKEND_AUTO);
    // 256 samples even with SS_TEST_QUICK: the reference's own steps are the yardstick, and at
    // 64 its noise alone doubles them.
    const int refSamples = 256;
    struct Case {
        LightType type;
        float yaw;
    };
    for (Case c : {Case{LightType::Square, 0.0f}, Case{LightType::Square, 30.0f}, Case{LightType::Disk, 0.0f}}) {
        Scene scene = widePenumbraScene(c.type, c.yaw);
        SweepOptions o;
        o.passes = 0;
        SweepShadow shadow = computeSweepShadow(scene, 0, o);
        EXPECT_EQ(shadow.passes, kSweepMaxPasses) << "the penumbra is about 3.4 rings' worth of pixels per ring";
        EXPECT_EQ(shadow.samplesUsed, kSweepMaxPasses * kSweepDefaultSamples);

        Layers ref = run(renderer, scene, "reference", refSamples);
        Layers one = run(renderer, scene, "sweep", 0, {{"passes", "1"}});
        Layers automatic = run(renderer, scene, "sweep", 0);
        Image mask = both(layer(ref, "mask"), layer(automatic, "mask"));
        const double refStep = neighbourStep(layer(ref, "V"), layer(ref, "V"), mask);
        const double oneStep = neighbourStep(layer(one, "V"), layer(ref, "V"), mask);
        const double autoStep = neighbourStep(layer(automatic, "V"), layer(ref, "V"), mask);
        Metrics eOne = compareVisibility(layer(one, "V"), layer(ref, "V"), &mask);
        Metrics eAuto = compareVisibility(layer(automatic, "V"), layer(ref, "V"), &mask);
        std::printf("%s yaw %.0f: p99 step one set %.4f, auto %.4f, reference %.4f; RMSE one set %.4f, auto %.4f\n",
                    lightTypeName(c.type), c.yaw, oneStep, autoStep, refStep, eOne.rmse, eAuto.rmse);
        const std::string name = std::string(lightTypeName(c.type)) + " yaw " + std::to_string(int(c.yaw));
        EXPECT_GT(oneStep, 2.0 * refStep + 0.005) << name << ": one set of 16 samples bands the penumbra";
        EXPECT_LE(autoStep, 2.0 * refStep + 0.005) << name;
        EXPECT_LT(eAuto.rmse, eOne.rmse) << name;
        EXPECT_LT(eAuto.rmse, 0.02) << name;
    }
}

// The count follows the penumbra on screen: 1 for a narrow one or a far camera, up to the cap
// for a wide one close up; an explicit count is kept as given.
TEST(SweepWidePenumbra, PassesFollowThePenumbraOnScreen) {
    Scene scene = widePenumbraScene(LightType::Square, 0.0f);
    SweepOptions o;
    o.passes = 0;
    const SweepShadow shadow = computeSweepShadow(scene, 0, o);
    // The plate's top edge, 1.7 m up under a 2 m light at 4 m: 2 x 1.7 / 2.3.
    EXPECT_NEAR(shadow.widest.width, 2.0 * 1.7 / 2.3, 1e-4);
    Camera far = makeLookAtCamera({0.0f, -25.0f, 80.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                  glm::radians(45.0f), 320, 240, 0.1f, 500.0f);
    EXPECT_EQ(autoSweepPasses(shadow.widest, far, 16), 1);
    EXPECT_EQ(autoSweepPasses(shadow.widest, scene.camera(), 16), kSweepMaxPasses);
    EXPECT_EQ(autoSweepPasses(shadow.widest, scene.camera(), 64), 1);
    EXPECT_EQ(autoSweepPasses(WidestPenumbra{}, scene.camera(), 16), 1);  // no penumbra
    o.passes = 2;
    EXPECT_EQ(computeSweepShadow(scene, 0, o).passes, 2);
    // Each pass its own sample set, drawn additively: one part per pass.
    EXPECT_EQ(shadow.parts.size(), size_t(kSweepMaxPasses));
}

}  // namespace
}  // namespace ss
