// Do n hard outlines merge into nested rings with exact intensities, the umbra where all
// samples overlap, and a shadow mesh that covers the union with the right intensity?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>
#include <polyclipping/clipper.hpp>

#include <cmath>
#include <cstdlib>
#include <random>

#include "planar/outline.h"
#include "planar/penumbra_fill.h"
#include "planar/rings.h"
#include "test_planar_shapes.h"
#include "planar_oracles/level_rings.h"

using namespace ss::planar;
using ss::planar::test::rectEdges;

namespace {

double integral(const ShadowMesh& m) {
    double sum = 0;
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        const ShadowVertex& a = m.vertices[m.indices[i]];
        const ShadowVertex& b = m.vertices[m.indices[i + 1]];
        const ShadowVertex& c = m.vertices[m.indices[i + 2]];
        double area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
        sum += area * (a.intensity + b.intensity + c.intensity) / 3.0;
    }
    return sum;
}

// Intensity at (x, y) by barycentric interpolation in the triangle holding it; -1 outside.
double sampleAt(const ShadowMesh& m, double x, double y) {
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        const ShadowVertex& a = m.vertices[m.indices[i]];
        const ShadowVertex& b = m.vertices[m.indices[i + 1]];
        const ShadowVertex& c = m.vertices[m.indices[i + 2]];
        double d = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        double l1 = ((x - a.x) * (c.y - a.y) - (y - a.y) * (c.x - a.x)) / d;
        double l2 = ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)) / d;
        double l0 = 1 - l1 - l2;
        if (l0 >= 0 && l1 >= 0 && l2 >= 0) return l0 * a.intensity + l1 * b.intensity + l2 * c.intensity;
    }
    return -1;
}

ClipperLib::Paths toPaths(const std::vector<Chain>& chains) {
    ClipperLib::Paths out;
    for (const Chain& c : chains) {
        ClipperLib::Path p;
        for (const IPoint& v : c) p.push_back(ClipperLib::IntPoint(v.x, v.y));
        out.push_back(p);
    }
    return out;
}

double area(const ClipperLib::Paths& p) {
    double a = 0;
    for (const auto& q : p) a += ClipperLib::Area(q);
    return std::fabs(a);
}

}  // namespace

// n squares of side S, each shifted by d: count >= k is the x range [(k-1)d, (n-k)d + S].
class TranslatedSquares : public ::testing::Test {
protected:
    static constexpr int n = 5;
    static constexpr int64_t d = 10000, S = 100000, H = 50000;
    std::vector<std::vector<DirectedEdge>> outlines;
    void SetUp() override {
        for (int i = 0; i < n; ++i) outlines.push_back(hardOutline(rectEdges(i * d, 0, i * d + S, H)));
    }
};

TEST_F(TranslatedSquares, RingAreasAndIntensitiesAreExact) {
    std::vector<Ring> rings = buildRings(mergeOutlines(outlines), n);
    ASSERT_EQ(rings.size(), size_t(n));
    for (int k = 1; k <= n; ++k) {
        const Ring& r = rings[k - 1];
        EXPECT_EQ(r.level, k);
        EXPECT_EQ(r.intensity, float(k - 1) / float(n - 1));
        EXPECT_EQ(regionArea(r.chains), double(((n - k) * d + S - (k - 1) * d) * H)) << "ring " << k;
        EXPECT_EQ(r.chains.size(), 1u);
    }
}

TEST_F(TranslatedSquares, SmoothFillIsLinearAcrossEachStrip) {
    ShadowMesh m = fillShadow(mergeOutlines(outlines), n, FillMode::Smooth);
    EXPECT_DOUBLE_EQ(m.shadowArea, double((S + (n - 1) * d) * H));
    EXPECT_DOUBLE_EQ(m.umbraArea, double((S - (n - 1) * d) * H));
    // Strip k (count k) spans ring k at x = (k-1)d (intensity (k-1)/(n-1)) to ring k+1.
    for (int k = 1; k < n; ++k)
        for (double f : {0.25, 0.5, 0.75})
            EXPECT_NEAR(sampleAt(m, (k - 1 + f) * d, H / 3.0), (k - 1 + f) / (n - 1), 1e-6) << "strip " << k;
    EXPECT_NEAR(sampleAt(m, S / 2.0 + d, H / 2.0), 1.0, 1e-9);
    // The mean of n shifted squares has the area of one: the integral of intensity is S * H.
    EXPECT_NEAR(integral(m), double(S * H), 1e-9 * S * H);
}

TEST_F(TranslatedSquares, StepFillIsCountOverN) {
    ShadowMesh m = fillShadow(mergeOutlines(outlines), n, FillMode::Steps);
    for (int k = 1; k <= n; ++k) EXPECT_FLOAT_EQ(sampleAt(m, (k - 0.5) * d, H / 2.0), float(k) / n);
    // Intensities are floats (k/n rounds at 6e-8 relative).
    EXPECT_NEAR(integral(m), double(S * H), 1e-7 * S * H);
}

TEST(PlanarRings, SingleSampleIsHardShadow) {
    std::vector<std::vector<DirectedEdge>> o = {hardOutline(rectEdges(0, 0, 100, 100))};
    ShadowMesh m = fillShadow(mergeOutlines(o), 1, FillMode::Smooth);
    for (const ShadowVertex& v : m.vertices) EXPECT_EQ(v.intensity, 1.0f);
    EXPECT_EQ(m.umbraArea, 10000.0);
}

// Random samples: each "sample" is the same random triangle set shifted by a random offset
// (what a light sample does to a shadow, roughly). Checked against Clipper: ring 1 is the
// union, ring n (the umbra) the intersection of all n hard shadows, rings nested, and the fill's
// intensity integral equals the mean hard-shadow area for the step fill (the Monte Carlo
// estimate). The smooth fill is not that estimate: a count-c region is shaded between its rings'
// intensities (c-1)/(n-1) and c/(n-1), so a bay bounded only by ring c sits at (c-1)/(n-1)
// (docs/methods/sweep.md: small occluders lose their lightest penumbra); its integral must lie
// between those two bounds, computed from the step fill's per-count areas.
TEST(PlanarRings, RandomSamplesMatchClipperUnionAndIntersection) {
    std::mt19937 rng(5);
    const int cases = std::getenv("SS_TEST_QUICK") ? 15 : 60;
    for (int c = 0; c < cases; ++c) {
        std::uniform_int_distribution<int64_t> coord(-300000, 300000), shift(-40000, 40000);
        std::uniform_int_distribution<int> count(1, 6), samplesDist(2, 9);
        int n = samplesDist(rng);
        std::vector<std::array<IPoint, 3>> base;
        for (int i = count(rng); i > 0; --i) {
            std::array<IPoint, 3> t = {IPoint{coord(rng), coord(rng)}, IPoint{coord(rng), coord(rng)},
                                       IPoint{coord(rng), coord(rng)}};
            if (orient(t[0], t[1], t[2]) == 0) continue;
            if (orient(t[0], t[1], t[2]) > 0) std::swap(t[1], t[2]);
            base.push_back(t);
        }
        if (base.empty()) continue;
        std::vector<std::vector<DirectedEdge>> outlines;
        std::vector<ClipperLib::Paths> shadows;
        double meanArea = 0;
        for (int s = 0; s < n; ++s) {
            int64_t dx = shift(rng), dy = shift(rng);
            std::vector<DirectedEdge> e;
            ClipperLib::Paths tris;
            for (auto& t : base) {
                ClipperLib::Path p;
                for (int k = 0; k < 3; ++k) {
                    IPoint a{t[k].x + dx, t[k].y + dy}, b{t[(k + 1) % 3].x + dx, t[(k + 1) % 3].y + dy};
                    e.push_back({a, b, 1});
                    p.push_back(ClipperLib::IntPoint(a.x, a.y));
                }
                tris.push_back(p);
            }
            outlines.push_back(hardOutline(e));
            ClipperLib::Clipper u;
            u.AddPaths(tris, ClipperLib::ptSubject, true);
            ClipperLib::Paths un;
            u.Execute(ClipperLib::ctUnion, un, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
            shadows.push_back(un);
            meanArea += area(un) / n;
        }
        ClipperLib::Paths uni = shadows[0], inter = shadows[0];
        for (int s = 1; s < n; ++s) {
            ClipperLib::Clipper a, b;
            a.AddPaths(uni, ClipperLib::ptSubject, true);
            a.AddPaths(shadows[s], ClipperLib::ptClip, true);
            a.Execute(ClipperLib::ctUnion, uni, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
            b.AddPaths(inter, ClipperLib::ptSubject, true);
            b.AddPaths(shadows[s], ClipperLib::ptClip, true);
            b.Execute(ClipperLib::ctIntersection, inter, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        }
        std::vector<DirectedEdge> merged = mergeOutlines(outlines);
        std::vector<Ring> rings = buildRings(merged, n);
        // Rounded crossings move outlines by < 1 unit; perimeters here are < 1e7 units.
        double tol = 2e7 + 1e-7 * area(uni);
        EXPECT_NEAR(regionArea(rings.front().chains), area(uni), tol) << "case " << c;
        EXPECT_NEAR(regionArea(rings.back().chains), area(inter), tol) << "case " << c;
        for (int k = 1; k < n; ++k) {
            // Nested: ring k+1's region minus ring k's region is empty.
            ClipperLib::Clipper diff;
            diff.AddPaths(toPaths(rings[k].chains), ClipperLib::ptSubject, true);
            diff.AddPaths(toPaths(rings[k - 1].chains), ClipperLib::ptClip, true);
            ClipperLib::Paths out;
            diff.Execute(ClipperLib::ctDifference, out, ClipperLib::pftNegative, ClipperLib::pftNegative);
            EXPECT_LT(area(out), tol) << "case " << c << " ring " << k + 1;
        }
        ShadowMesh steps = fillShadow(merged, n, FillMode::Steps);
        EXPECT_NEAR(steps.shadowArea, area(uni), tol);
        EXPECT_NEAR(steps.umbraArea, area(inter), tol);
        EXPECT_NEAR(integral(steps), meanArea, tol);
        ShadowMesh smooth = fillShadow(merged, n, FillMode::Smooth);
        for (const ShadowVertex& v : smooth.vertices) {
            ASSERT_GE(v.intensity, 0.0f);
            ASSERT_LE(v.intensity, 1.0f);
        }
        double lower = 0, upper = 0;
        for (size_t i = 0; i < steps.indices.size(); i += 3) {
            const ShadowVertex& a = steps.vertices[steps.indices[i]];
            const ShadowVertex& b = steps.vertices[steps.indices[i + 1]];
            const ShadowVertex& q = steps.vertices[steps.indices[i + 2]];
            double ar = 0.5 * ((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x));
            int count = int(std::lround(a.intensity * n));
            lower += ar * ringIntensity(count, n);
            upper += ar * std::min(1.0f, ringIntensity(count + 1, n));
        }
        double got = integral(smooth);
        EXPECT_GE(got, lower - tol) << "case " << c;
        EXPECT_LE(got, upper + tol) << "case " << c;
        EXPECT_GT(upper - lower, 0.0);
    }
}
