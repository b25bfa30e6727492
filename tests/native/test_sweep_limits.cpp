// How large are the sweep paper's own limits in this code: Mach bands from the Gouraud steps,
// shadows that jump as the light samples move, and penumbrae too small with few samples?
// Measured on the box scene along a profile across its right penumbra, against the exact
// equal-weight visibility of the disk light (the paper weighs samples equally, so does this).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "io/png_preview.h"
#include "methods/sweep/lookup.h"
#include "methods/sweep/shadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

// The box of test::sceneBox, the disk light of its SceneParams.
constexpr double kBoxLo[3] = {-0.6, -0.6, 0.8}, kBoxHi[3] = {0.6, 0.6, 1.2};
constexpr double kLightRadius = 0.75, kLightHeight = 4.0;

// Fraction of the disk light (centre x = lightX, radius r at z = 4) hidden from ground point
// (x, 0, 0), exact: seen from there the box covers the light plane up to x' = R(x), the larger
// of its top (z = 1.2) and bottom (z = 0.8) right edges projected from the point, over the
// whole height of the disk (0.6 * 4/1.2 > r), so the hidden part is a circular segment.
double exactIntensity(double lightX, double x) {
    double R = std::max(x + (kBoxHi[0] - x) * kLightHeight / kBoxHi[2], x + (kBoxHi[0] - x) * kLightHeight / kBoxLo[2]);
    double d = std::clamp((R - lightX) / kLightRadius, -1.0, 1.0);
    return (M_PI - std::acos(d) + d * std::sqrt(1.0 - d * d)) / M_PI;
}

struct Profile {
    std::vector<double> x, value;
};

constexpr double kX0 = 0.40, kX1 = 1.30;

Profile sweepProfile(const SweepShadow& sh, int points, double y = 0.0) {
    ShadowLookup lookup(sh.mesh);
    Profile p;
    for (int i = 0; i < points; ++i) {
        double x = kX0 + (kX1 - kX0) * i / (points - 1);
        glm::dvec2 uv = sh.plane.toPlane({x, y, 0.0});
        p.x.push_back(x);
        p.value.push_back(lookup.intensity((uv.x - sh.plane.cu) * sh.snap.scale(), (uv.y - sh.plane.cv) * sh.snap.scale()));
    }
    return p;
}

Profile exactProfile(double lightX, int points) {
    Profile p;
    for (int i = 0; i < points; ++i) {
        double x = kX0 + (kX1 - kX0) * i / (points - 1);
        p.x.push_back(x);
        p.value.push_back(exactIntensity(lightX, x));
    }
    return p;
}

SweepShadow shadow(planar::FillMode fill, int samples, double lightX = 0.0, uint32_t seed = 1) {
    test::SceneParams params;
    params.lightShift = {float(lightX), 0.0f};
    Scene scene = test::sceneBox(params);
    SweepOptions o;
    o.samples = samples;
    o.seed = seed;
    o.fill = fill;
    o.irradianceWeights = false;
    return computeSweepShadow(scene, 0, o);
}

// Gradient steps along a profile: the largest jump of the slope between neighbouring
// intervals, and how many jumps exceed a quarter of the mean slope over the penumbra. A
// Gouraud-shaded mesh is linear inside each triangle, so its slope along a line is piecewise
// constant and jumps where the line crosses a triangle side: the Mach bands.
struct Steps {
    double largest = 0;  // relative to the mean slope
    int count = 0;
};
Steps gradientSteps(const Profile& p) {
    const double h = p.x[1] - p.x[0];
    std::vector<double> g;
    for (size_t i = 0; i + 1 < p.x.size(); ++i) g.push_back((p.value[i + 1] - p.value[i]) / h);
    double mean = std::abs(p.value.back() - p.value.front()) / (p.x.back() - p.x.front());
    Steps s;
    for (size_t i = 0; i + 1 < g.size(); ++i) {
        double jump = std::abs(g[i + 1] - g[i]) / mean;
        s.largest = std::max(s.largest, jump);
        s.count += jump > 0.25;
    }
    return s;
}

// Where the profile leaves the umbra (last value >= 1 - eps) and reaches the lit side (first
// value <= eps after it).
double penumbraWidth(const Profile& p, double eps) {
    size_t inner = 0, outer = p.x.size() - 1;
    for (size_t i = 0; i < p.x.size(); ++i)
        if (p.value[i] >= 1.0 - eps) inner = i;
    for (size_t i = inner; i < p.x.size(); ++i)
        if (p.value[i] <= eps) {
            outer = i;
            break;
        }
    return p.x[outer] - p.x[inner];
}

double rmse(const Profile& a, const Profile& b) {
    double s = 0;
    for (size_t i = 0; i < a.value.size(); ++i) s += (a.value[i] - b.value[i]) * (a.value[i] - b.value[i]);
    return std::sqrt(s / double(a.value.size()));
}

// The penumbra on the ground at y = 0: it starts where the bottom edge (x = 0.6, z = 0.8) hides
// the light's right end, 3 - 4x = 0.75, and ends where the top edge (z = 1.2) uncovers its left
// end, 2 - 7x/3 = -0.75: [0.5625, 1.1786], 0.616 wide.
constexpr double kTrueWidth = 33.0 / 28.0 - 0.5625;

}  // namespace

// Mach bands: the smooth and ring fills' slope jumps along the profile (16 samples) against
// the exact profile's, which has none above a quarter of the mean slope. Steps (count / n)
// jumps by 1/n in value instead.
TEST(SweepLimits, GouraudStepsAlongAPenumbraProfile) {
    const int points = 451;  // 0.002 apart
    Profile exact = exactProfile(0.0, points);
    Steps e = gradientSteps(exact);
    EXPECT_NEAR(penumbraWidth(exact, 1e-4), kTrueWidth, 0.01);
    std::printf("exact: largest slope jump %.2f x mean, %d jumps > 0.25\n", e.largest, e.count);
    // One real kink: at x = 0.6 the hiding edge passes from the bottom to the top of the box.
    EXPECT_LE(e.count, 2);
    for (auto [name, fill] : {std::pair{"smooth", planar::FillMode::Smooth}, std::pair{"rings", planar::FillMode::Rings}}) {
        Profile p = sweepProfile(shadow(fill, 16), points);
        Steps s = gradientSteps(p);
        std::printf("%s (16): largest slope jump %.2f x mean, %d jumps > 0.25, profile RMSE %.4f\n", name, s.largest,
                    s.count, rmse(p, exact));
        // The limit is there: slope jumps of the order of the mean slope itself.
        EXPECT_GT(s.largest, 0.5) << name;
        EXPECT_GE(s.count, 3) << name;
        EXPECT_LT(rmse(p, exact), 0.06) << name;
    }
    // Optional picture for the docs: smooth | rings | steps over the box's shadow (16 samples),
    // and under each its slope magnitude, where the Gouraud steps show as lines (Mach bands).
    if (const char* path = std::getenv("SS_SWEEP_LIMITS_PNG")) {
        const int S = 160;
        const SweepShadow sh[3] = {shadow(planar::FillMode::Smooth, 16), shadow(planar::FillMode::Rings, 16),
                                   shadow(planar::FillMode::Steps, 16)};
        const ShadowLookup lookups[3] = {ShadowLookup(sh[0].mesh), ShadowLookup(sh[1].mesh), ShadowLookup(sh[2].mesh)};
        Image img(3 * S, 2 * S, 1.0f);
        auto at = [&](int panel, double x, double y) -> double {
            glm::dvec2 uv = sh[panel].plane.toPlane({x, y, 0.0});
            return lookups[panel].intensity((uv.x - sh[panel].plane.cu) * sh[panel].snap.scale(),
                                            (uv.y - sh[panel].plane.cv) * sh[panel].snap.scale());
        };
        for (int panel = 0; panel < 3; ++panel)
            for (int j = 0; j < S; ++j)
                for (int i = 0; i < S; ++i) {
                    // A corner of the shadow: x in [0.2, 1.4], y in [-1.4, -0.2].
                    double d = 1.2 / S, x = 0.2 + (i + 0.5) * d, y = -0.2 - (j + 0.5) * d;
                    double v = at(panel, x, y);
                    double gx = (at(panel, x + d, y) - v) / d, gy = (at(panel, x, y - d) - v) / d;
                    img.pixels[size_t(j) * 3 * S + panel * S + i] = float(1.0 - v);
                    img.pixels[size_t(j + S) * 3 * S + panel * S + i] =
                        float(std::clamp(1.0 - std::hypot(gx, gy) / 6.0, 0.0, 1.0));
                }
        writePngPreview(path, img);
    }
}

// Penumbrae too small with few samples: the sweep's penumbra (ring 1 to ring n) spans only
// the samples' extent, so it is narrower than the light's; it widens towards the true width
// as the count grows (a quarter of the samples sit on the border).
TEST(SweepLimits, PenumbraWidthGrowsWithSampleCount) {
    const int points = 901;  // 0.001 apart
    double previous = 0.0;
    for (int n : {3, 4, 8, 16, 32, 64, 256}) {
        Profile p = sweepProfile(shadow(planar::FillMode::Smooth, n), points);
        double ratio = penumbraWidth(p, 1e-6) / kTrueWidth;
        std::printf("n=%d: penumbra width %.3f of the true %.3f (%.3f)\n", n, ratio * kTrueWidth, kTrueWidth, ratio);
        EXPECT_LE(ratio, 1.0 + 0.005) << "n=" << n;  // never wider than the light allows
        if (n <= 4) {
            EXPECT_LT(ratio, 0.85) << "n=" << n;
        }
        if (n >= 64) {
            EXPECT_GT(ratio, 0.95) << "n=" << n;
        }
        EXPECT_GE(ratio, previous - 0.03) << "n=" << n;
        previous = ratio;
    }
}

// Shadows that jump as the light moves: the light slides 0.2 in x over 41 frames. Roughness is
// the RMS over penumbra points and frames of the second difference in time, I(t+1) - 2 I(t) +
// I(t-1), which a shadow moving smoothly keeps near 0. Samples fixed to the light (same seed)
// and samples drawn anew each frame (seed = frame) against the exact profile's.
TEST(SweepLimits, ShadowJitterUnderAnAnimatedLight) {
    const int points = 181, frames = 41;
    auto roughness = [&](auto&& profileAt) {
        std::vector<Profile> f;
        for (int t = 0; t < frames; ++t) f.push_back(profileAt(t, -0.1 + 0.2 * t / (frames - 1)));
        double sum = 0, largest = 0;
        int count = 0;
        for (int t = 1; t + 1 < frames; ++t)
            for (int i = 0; i < points; ++i) {
                double v = f[t].value[i];
                if (v <= 0.0 || v >= 1.0) continue;
                double d2 = f[t + 1].value[i] - 2.0 * v + f[t - 1].value[i];
                sum += d2 * d2;
                largest = std::max(largest, std::abs(d2));
                ++count;
            }
        return std::pair{std::sqrt(sum / std::max(count, 1)), largest};
    };
    auto exact = roughness([&](int, double lx) { return exactProfile(lx, points); });
    std::printf("exact: roughness %.4f, largest %.4f\n", exact.first, exact.second);
    EXPECT_LT(exact.first, 0.001);
    for (auto [name, fill] : {std::pair{"smooth", planar::FillMode::Smooth}, std::pair{"rings", planar::FillMode::Rings},
                              std::pair{"steps", planar::FillMode::Steps}}) {
        auto fixed = roughness([&](int, double lx) { return sweepProfile(shadow(fill, 16, lx, 1), points); });
        auto redrawn = roughness([&](int t, double lx) { return sweepProfile(shadow(fill, 16, lx, uint32_t(t + 1)), points); });
        std::printf("%s (16): roughness fixed samples %.4f (largest %.3f), redrawn %.4f (largest %.3f)\n", name,
                    fixed.first, fixed.second, redrawn.first, redrawn.second);
        // The limit is there: well above the smooth motion's, and worse when samples are redrawn.
        EXPECT_GT(fixed.first, 2.0 * exact.first) << name;
        EXPECT_GT(redrawn.first, fixed.first) << name;
    }
}

}  // namespace ss
