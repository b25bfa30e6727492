// How much does `sweep` lose by counting every light sample equally, where the visibility
// contract weighs each light point by the irradiance it sends (cos at both ends / distance^2)?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/metrics.h"
#include "methods/sweep/shadow.h"
#include "methods/sweep/weights.h"
#include "renderer/renderer.h"
#include "sampling/light_samples.h"
#include "test_scenes.h"

namespace ss {
namespace {

// Whether the segment p -> s meets the open box [lo, hi] (slab test).
bool blocked(const glm::dvec3& p, const glm::dvec3& s, const glm::dvec3& lo, const glm::dvec3& hi) {
    double t0 = 0.0, t1 = 1.0;
    for (int a = 0; a < 3; ++a) {
        double d = s[a] - p[a];
        if (std::fabs(d) < 1e-15) {
            if (p[a] <= lo[a] || p[a] >= hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - p[a]) / d, tb = (hi[a] - p[a]) / d;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 >= t1) return false;
    }
    return true;
}

struct WeightBias {
    double max = 0, rms = 0;  // |V_equal - V_weighted| over ground points in the penumbra
    size_t points = 0;
};

// The shared box (top 1.2, 1.2 wide) under a downward disk light of diameter `d` at height `h`:
// on a ground grid, V with equal sample weights against V with the contract's weights
// h^2 / dist^4 (both cosines are h / dist for a downward light over an upward plane), from the
// very same 1024 samples, so the difference is the weighting alone, not sampling noise.
WeightBias weightBias(float d, float h) {
    Light light = test::makeDiskLight({0.0f, 0.0f, h}, d);
    LightSampleOptions o;
    o.count = 1024;
    std::vector<LightSample> samples = placeLightSamples(light, o);
    const glm::dvec3 lo(-0.6, -0.6, 0.8), hi(0.6, 0.6, 1.2);
    WeightBias b;
    double sum2 = 0;
    for (int j = 0; j <= 120; ++j)
        for (int i = 0; i <= 120; ++i) {
            glm::dvec3 p(-3.0 + 0.05 * i, -3.0 + 0.05 * j, 0.0);
            double litE = 0, allE = 0, litN = 0;
            for (const LightSample& s : samples) {
                glm::dvec3 r = s.point - p;
                double dist2 = glm::dot(r, r);
                double w = r.z * r.z / (dist2 * dist2);
                bool lit = !blocked(p, s.point, lo, hi);
                allE += w;
                litE += lit ? w : 0.0;
                litN += lit ? 1.0 : 0.0;
            }
            double ve = litN / samples.size(), vw = litE / allE;
            if (ve <= 0.0 || ve >= 1.0) continue;  // fully lit or umbra: no bias there
            double e = std::fabs(ve - vw);
            b.max = std::max(b.max, e);
            sum2 += e * e;
            ++b.points;
        }
    b.rms = b.points ? std::sqrt(sum2 / b.points) : 0.0;
    return b;
}

// Measured: the shared scenes' light (1.5 wide, 4 up) max 0.037, RMS 0.026 over penumbra
// points; a 4-wide light 2 up (0.8 above the box) max 0.22, RMS 0.15 (every grid point is in
// its penumbra). Asserted: shared < 0.05, large-close > 3x shared and > 0.15.
TEST(SweepWeights, EqualWeightBiasGrowsWithLargeCloseLights) {
    WeightBias shared = weightBias(1.5f, 4.0f);
    WeightBias close = weightBias(4.0f, 2.0f);
    std::printf("equal-weight bias, light 1.5 at 4: max %.4f rms %.4f (%zu penumbra points)\n", shared.max,
                shared.rms, shared.points);
    std::printf("equal-weight bias, light 4 at 2: max %.4f rms %.4f (%zu penumbra points)\n", close.max, close.rms,
                close.points);
    EXPECT_GT(shared.points, 500u);
    EXPECT_GT(close.points, 500u);
    EXPECT_LT(shared.max, 0.05);
    EXPECT_GT(close.max, 3.0 * shared.max);
    EXPECT_GT(close.max, 0.15);
}

// Rendered: sweep (64 samples) against reference (256) on the box under the large, close light
// (4 wide, 2 up), with irradiance weights (the default) and with equal weights. Measured RMSE
// over receiver pixels: 0.0093 weighted, 0.110 equal (lit IoU 0.97 vs 0.43: equal weights
// darken the whole floor, all of it in penumbra). Bounds: weighted < 0.02 (the shared scenes'
// bound is 0.03), equal > 5x weighted.
TEST(SweepWeights, LargeCloseLightAgainstReference) {
    Renderer renderer(SS_BACKEND_AUTO);
    const int refSamples = test::quickTests() ? 64 : 256;
    test::SceneParams p;
    p.lightDiameter = 4.0f;
    p.lightHeight = 2.0f;
    Scene scene = test::sceneBox(p);
    RenderSettings s;
    std::string used;
    s.samples = refSamples;
    Layers ref = renderer.render(scene, 0, "reference", s, &used);
    double rmse[2];
    for (int k = 0; k < 2; ++k) {
        s.samples = 64;
        s.options = {{"weights", k == 0 ? "irradiance" : "equal"}};
        Layers sw = renderer.render(scene, 0, "sweep", s, &used);
        Image mask = *sw.find("mask");
        const Image& rm = *ref.find("mask");
        for (size_t i = 0; i < mask.pixels.size(); ++i) mask.pixels[i] *= rm.pixels[i] > 0.5f ? 1.0f : 0.0f;
        Metrics m = compareVisibility(*sw.find("V"), *ref.find("V"), &mask);
        std::printf("box, light 4 at 2, sweep 64 weights=%s vs reference: %s\n", k == 0 ? "irradiance" : "equal",
                    m.toString().c_str());
        EXPECT_GT(m.pixels, 10000u);
        rmse[k] = m.rmse;
    }
    EXPECT_LT(rmse[0], 0.02);
    EXPECT_GT(rmse[1], 5.0 * rmse[0]);
}

// With fill=steps the weighted mesh is exact per corner: I = W_S / W with S the samples whose
// hard shadow holds the triangle (checked here by ray against the box, independently of the
// outlines) and W the contract's weights at the corner. Tolerance 1e-4 (float intensities,
// corners rounded to the grid, 5e-7 of the receiver). Measured: 0 of ~700 non-degenerate
// triangles disagree; at most 0.5 % may (a centroid within a grid unit of a sample's shadow
// edge, where snapping decides).
TEST(SweepWeights, StepsCornersAreWeightedShares) {
    test::SceneParams p;
    p.lightDiameter = 4.0f;
    p.lightHeight = 2.0f;
    Scene scene = test::sceneBox(p);
    SweepOptions o;
    o.fill = planar::FillMode::Steps;
    SweepShadow sh = computeSweepShadow(scene, 0, o);
    ASSERT_EQ(sh.samplesUsed, 16);
    LightSampleOptions so;
    so.count = 16;
    so.seed = o.seed;
    so.borderShare = o.borderShare;
    const Light& light = scene.lights()[0];
    std::vector<LightSample> samples = placeLightSamples(light, so);
    const glm::dvec3 lo(-0.6, -0.6, 0.8), hi(0.6, 0.6, 1.2), up(0, 0, 1);
    size_t triangles = sh.mesh.indices.size() / 3, mismatched = 0;
    ASSERT_GT(triangles, 10u);
    size_t degenerate = 0;
    for (size_t t = 0; t < triangles; ++t) {
        const auto& a = sh.mesh.vertices[sh.mesh.indices[3 * t]];
        const auto& b = sh.mesh.vertices[sh.mesh.indices[3 * t + 1]];
        const auto& d = sh.mesh.vertices[sh.mesh.indices[3 * t + 2]];
        // Zero-area triangles (a trapezoid narrowing to a point) cover nothing; their centroid
        // lies on an outline, so their S is arbitrary.
        if (std::fabs((b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x)) < 1.0) {
            ++degenerate;
            continue;
        }
        glm::dvec3 c(0.0);
        for (int j = 0; j < 3; ++j) c += sh.worldVertex(sh.mesh.indices[3 * t + j]) / 3.0;
        std::vector<bool> shadowed;
        for (const LightSample& s : samples) shadowed.push_back(blocked(c, s.point, lo, hi));
        bool ok = true;
        for (int j = 0; j < 3; ++j) {
            glm::dvec3 v = sh.worldVertex(sh.mesh.indices[3 * t + j]);
            double all = 0, in = 0;
            for (size_t k = 0; k < samples.size(); ++k) {
                double w = sampleIrradianceWeight(light, samples[k], v, up);
                all += w;
                in += shadowed[k] ? w : 0.0;
            }
            ok = ok && std::fabs(sh.mesh.vertices[sh.mesh.indices[3 * t + j]].intensity - in / all) < 1e-4;
        }
        mismatched += !ok;
    }
    std::printf("weighted steps: %zu of %zu triangles differ (%zu degenerate skipped)\n", mismatched, triangles,
                degenerate);
    EXPECT_LT(degenerate, triangles / 2);
    EXPECT_LE(mismatched, triangles / 200);
}

}  // namespace
}  // namespace ss
