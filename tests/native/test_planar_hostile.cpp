// Does the planar core survive hostile input — self-intersecting closed polylines with weights,
// edges on the grid limits, piles of duplicate and collinear edges — with its invariants intact
// (a bounded stand-in for the fuzz target the issue asks for)? Inputs are closed cycles, as
// every caller's are (projected silhouettes, triangles, clipped pieces, outlines).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "planar/outline.h"
#include "planar/penumbra_fill.h"
#include "planar/trapezoids.h"

using namespace ss::planar;

namespace {

std::vector<DirectedEdge> randomSoup(std::mt19937& rng, int kind) {
    const int64_t L = kGridLimit;
    std::vector<DirectedEdge> e;
    std::uniform_int_distribution<int> count(1, 40);
    // kind 0: anywhere on the grid; 1: a 3x3 lattice spanning the whole grid (everything
    // collinear, duplicate or meeting at vertices); 2: a tiny cluster (slivers, crossings at
    // near-identical x).
    std::uniform_int_distribution<int64_t> any(-L, L), lattice(-1, 1), tiny(-3, 3);
    auto coord = [&]() -> int64_t {
        switch (kind) {
            case 0: return any(rng);
            case 1: return lattice(rng) * L;
            default: return tiny(rng) + 1000;
        }
    };
    for (int loops = std::uniform_int_distribution<int>(1, 4)(rng); loops > 0; --loops) {
        int w = std::uniform_int_distribution<int>(-2, 2)(rng);
        std::vector<IPoint> p;
        for (int i = count(rng) / 4 + 2; i > 0; --i) p.push_back({coord(), coord()});
        for (size_t i = 0; i < p.size(); ++i) e.push_back({p[i], p[(i + 1) % p.size()], w == 0 ? 1 : w});
    }
    return e;
}

}  // namespace

// Invariants for any closed edge set: trapezoids are well formed, the boundary links into closed chains
// enclosing the same area as the trapezoids (tolerance: rounded crossings, < 1.5 units per unit
// of boundary length, plus 1 unit^2 per input edge for slivers thinner than a grid unit whose
// rounded boundary vanishes), and a fill stays within [0, 1].
TEST(PlanarHostile, SelfIntersectingWeightedLoopsKeepInvariants) {
    std::mt19937 rng(77);
    const int cases = std::getenv("SS_TEST_QUICK") ? 300 : 1500;
    for (int c = 0; c < cases; ++c) {
        std::vector<DirectedEdge> e = randomSoup(rng, c % 3);
        std::vector<SweepSegment> segs = toSweepSegments(e);
        double trapArea = 0;
        for (const Trapezoid& t : trapezoids(segs, [](int w) { return w >= 1; })) {
            ASSERT_LE(t.x0, t.x1) << "case " << c;
            ASSERT_GE(t.yTop0 - t.yBottom0, -1e-6) << "case " << c;
            ASSERT_GE(t.yTop1 - t.yBottom1, -1e-6) << "case " << c;
            trapArea += t.area();
        }
        std::vector<DirectedEdge> boundary = regionBoundary(segs, [](int w) { return w >= 1; });
        double length = 0;
        for (const DirectedEdge& d : boundary) length += std::hypot(double(d.b.x - d.a.x), double(d.b.y - d.a.y));
        std::vector<Chain> chains = linkChains(boundary);
        ASSERT_NEAR(regionArea(chains), trapArea, 1.5 * length + double(e.size()) + 1e-9 * trapArea) << "case " << c;
        ShadowMesh m = fillShadow(hardOutline(e), 3, FillMode::Smooth);
        for (const ShadowVertex& v : m.vertices) {
            ASSERT_GE(v.intensity, 0.0f);
            ASSERT_LE(v.intensity, 1.0f);
        }
    }
}
