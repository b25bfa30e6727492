// Checks the reference's V against closed forms: a coaxial disk occluder and a half-plane under a disk light.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/scene.h"
#include "reference/light_sampler.h"
#include "reference/sample_sequence.h"
#include "reference/trace_scene.h"
#include "reference/visibility_estimator.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

// Light: a disk of radius R at height h facing down; receiver: the plane z = 0.
constexpr double kR = 1.0, kH = 4.0;

Light disk() { return test::makeDiskLight({0.0f, 0.0f, float(kH)}, float(2.0 * kR)); }

// A horizontal disk polygon whose area equals the true disk's (vertex radius scaled up), so
// the polygon's shadow differs from the circle's by ~1e-6 in V, far below every tolerance here.
Mesh occluderDisk(float radius, float height, int segments = 256) {
    Mesh m;
    m.name = "occluder";
    double step = 2.0 * M_PI / segments;
    float vertexRadius = radius * float(std::sqrt(step / std::sin(step)));
    m.objectPositions.push_back({0.0f, 0.0f, height});
    for (int i = 0; i < segments; ++i)
        m.objectPositions.push_back({vertexRadius * float(std::cos(i * step)),
                                     vertexRadius * float(std::sin(i * step)), height});
    for (uint32_t i = 0; i < uint32_t(segments); ++i)
        m.triangles.push_back({0, 1 + i, 1 + (i + 1) % uint32_t(segments)});
    m.flags = SS_MESH_CAST;
    return m;
}

// The half-plane x > 0 at the given height (a big quad).
Mesh occluderHalfPlane(float height) {
    Mesh m;
    m.name = "half-plane";
    m.objectPositions = {{0, -60, height}, {60, -60, height}, {60, 60, height}, {0, 60, height}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.flags = SS_MESH_CAST;
    return m;
}

// The receiver point (x, 0, 0) as the reference finds it: a ray from just under the occluder.
SurfaceHit groundPoint(const TraceScene& trace, float x) {
    Ray down{{x, 0.0f, 0.5f}, {0.0f, 0.0f, -1.0f}};
    SurfaceHit h = trace.intersect(down, 0.0f, 10.0f);
    EXPECT_TRUE(h.hit);
    EXPECT_NEAR(h.normal.z, 1.0f, 1e-6f);
    return h;
}

Scene sceneWith(Mesh occluder) {
    Scene s;
    s.addMesh(test::makeGround(30.0f, 0.0f, SS_MESH_RECEIVE));
    s.addMesh(std::move(occluder));
    s.addLight(disk());
    return s;
}

// On the axis, a coaxial occluding disk of radius r_o at height h_o hides the light's central
// disk of radius rho = r_o h / h_o, and a centred disk of radius a sends pi a^2/(a^2 + h^2).
double coaxialDiskV(double ro, double ho) {
    double rho = ro * kH / ho;
    return 1.0 - (rho * rho / (rho * rho + kH * kH)) / (kR * kR / (kR * kR + kH * kH));
}

// The share of E from the part x > c of the disk light seen from (p, 0, 0), by quadrature:
// the inner integral over y is closed, int dy / (y^2 + a^2)^2 = y / (2a^2 (y^2+a^2))
// + atan(y/a) / (2a^3); the outer one runs over x = R sin(theta) (smooth in theta) with
// composite Simpson, 20000 intervals: error < 1e-10.
double diskIrradianceBeyond(double p, double c) {
    auto inner = [&](double x) {
        double Y = std::sqrt(std::max(0.0, kR * kR - x * x));
        double a2 = (x - p) * (x - p) + kH * kH, a = std::sqrt(a2);
        return kH * kH * (Y / (a2 * (Y * Y + a2)) + std::atan(Y / a) / (a2 * a));
    };
    double t0 = std::asin(std::clamp(c / kR, -1.0, 1.0)), t1 = 0.5 * M_PI;
    if (t1 <= t0) return 0.0;
    const int n = 20000;
    double step = (t1 - t0) / n, sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        double t = t0 + i * step;
        double f = inner(kR * std::sin(t)) * kR * std::cos(t);
        sum += f * ((i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return sum * step / 3.0;
}

// The half-plane x > 0 at height h_o hides, from (p, 0, 0), the light's part x > p (1 - h/h_o).
double halfPlaneV(double p, double ho) {
    double blocked = diskIrradianceBeyond(p, p * (1.0 - kH / ho));
    return 1.0 - blocked / diskIrradianceBeyond(p, -kR);
}

// Owen-scrambled (0,m,2)-nets have at most 2x the Monte Carlo variance (Owen 1997), and over
// this near-parallel disk the weights vary by less than 1.13x, so one estimate's standard
// error is below sqrt(2) * 1.13 * sqrt(V (1 - V) / N). Tolerances are 4 of these.
double fourSigma(double v, int n) { return 4.0 * std::sqrt(2.0) * 1.13 * std::sqrt(v * (1.0 - v) / n); }

// Scrambled nets integrate an indicator with a smooth edge with standard error O(N^-3/4)
// (He & Owen 2015); the constant measured here is ~0.2 (RMS 0.0004 at N = 4096), so
// 0.5 N^-3/4 bounds one estimate's standard error with room, and 4 of it catches a bias of
// 0.5% in V (e.g. a missing cosine at the light) that the Monte Carlo bound would let through.
double fourQmcSigma(int n) { return 4.0 * 0.5 * std::pow(double(n), -0.75); }

TEST(ReferenceClosedForm, CoaxialDiskOccluderOnAxis) {
    const float ro = 0.3f, ho = 2.0f;
    Scene scene = sceneWith(occluderDisk(ro, ho));
    TraceScene trace(scene);
    LightSampler light(scene.lights()[0]);
    SurfaceHit hit = groundPoint(trace, 0.0f);
    const double exact = coaxialDiskV(ro, ho);
    const int n = 4096, seeds = test::quickTests() ? 8 : 32;
    double mean = 0.0;
    for (int s = 0; s < seeds; ++s) {
        double v = estimateVisibility(trace, light, hit, SampleSequence(uint32_t(s), 0, 0), n).visibility;
        EXPECT_NEAR(v, exact, fourSigma(exact, n)) << "seed " << s << ": reference " << v
                                                   << ", closed form " << exact;
        mean += v / seeds;
    }
    EXPECT_NEAR(mean, exact, fourQmcSigma(n) / std::sqrt(double(seeds)))
        << "mean over " << seeds << " seeds " << mean << ", closed form " << exact;
}

TEST(ReferenceClosedForm, ErrorFallsAsSamplesGrow) {
    const float ro = 0.3f, ho = 2.0f;
    Scene scene = sceneWith(occluderDisk(ro, ho));
    TraceScene trace(scene);
    LightSampler light(scene.lights()[0]);
    SurfaceHit hit = groundPoint(trace, 0.0f);
    const double exact = coaxialDiskV(ro, ho);
    const int seeds = test::quickTests() ? 16 : 64;
    std::vector<double> rms;
    for (int n : {16, 256, 4096}) {
        double sq = 0.0;
        for (int s = 0; s < seeds; ++s) {
            double v = estimateVisibility(trace, light, hit, SampleSequence(uint32_t(s), 1, 1), n).visibility;
            sq += (v - exact) * (v - exact);
        }
        rms.push_back(std::sqrt(sq / seeds));
        std::printf("[ reference ] coaxial disk, %4d samples: RMS error %.5f (closed form V %.5f)\n",
                    n, rms.back(), exact);
    }
    // Plain Monte Carlo would shrink 4x per 16x samples; demand at least that.
    EXPECT_LT(rms[1], rms[0] / 4.0) << rms[0] << " -> " << rms[1];
    EXPECT_LT(rms[2], rms[1] / 4.0) << rms[1] << " -> " << rms[2];
    // Over 256x more samples, faster than Monte Carlo's 16x: stratification is doing its job.
    EXPECT_LT(rms[2], rms[0] / 32.0) << rms[0] << " -> " << rms[2];
}

TEST(ReferenceClosedForm, HalfPlaneOccluderAcrossThePenumbra) {
    const float ho = 2.0f;
    Scene scene = sceneWith(occluderHalfPlane(ho));
    TraceScene trace(scene);
    LightSampler light(scene.lights()[0]);
    const int n = 4096;
    // The penumbra on the ground is |x| < R / (h/h_o - 1) = 1: points across it and both sides.
    for (float x : {-1.3f, -0.9f, -0.6f, -0.3f, -0.1f, 0.0f, 0.1f, 0.3f, 0.6f, 0.9f, 1.3f}) {
        const double exact = halfPlaneV(x, ho);
        SurfaceHit hit = groundPoint(trace, x);
        double v = estimateVisibility(trace, light, hit, SampleSequence(11, uint32_t(100 * (x + 2)), 0), n).visibility;
        // At the fully lit / fully shadowed ends the estimate must be exact.
        double tol = (exact == 0.0 || exact == 1.0) ? 1e-6 : fourQmcSigma(n);
        EXPECT_NEAR(v, exact, tol) << "x = " << x << ": reference " << v << ", quadrature " << exact;
        std::printf("[ reference ] half-plane x = %+.1f: V %.5f, quadrature %.5f\n", x, v, exact);
    }
    EXPECT_NEAR(halfPlaneV(0.0, ho), 0.5, 1e-9);  // the quadrature itself: symmetry
}

TEST(ReferenceClosedForm, EstimateIsDeterministicForASeed) {
    Scene scene = sceneWith(occluderHalfPlane(2.0f));
    TraceScene trace(scene);
    LightSampler light(scene.lights()[0]);
    SurfaceHit hit = groundPoint(trace, 0.2f);
    float a = estimateVisibility(trace, light, hit, SampleSequence(3, 5, 6), 64).visibility;
    float b = estimateVisibility(trace, light, hit, SampleSequence(3, 5, 6), 64).visibility;
    float c = estimateVisibility(trace, light, hit, SampleSequence(4, 5, 6), 64).visibility;
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);  // another scramble of a penumbra point: the estimate moves
}

}  // namespace
}  // namespace ss
