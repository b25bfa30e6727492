// Which shadows does the split keep apart (those that do not meet) and together (crossing,
// nested, touching), and does filling the parts one by one give the whole fill's triangles?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <tuple>
#include <vector>

#include "planar/outline.h"
#include "planar/penumbra_fill.h"
#include "planar/rings.h"
#include "planar/shadow_parts.h"
#include "test_planar_shapes.h"

using namespace ss::planar;
using ss::planar::test::rectEdges;

namespace {

std::vector<DirectedEdge> join(std::initializer_list<std::vector<DirectedEdge>> pieces) {
    std::vector<DirectedEdge> all;
    for (const auto& p : pieces) all.insert(all.end(), p.begin(), p.end());
    return all;
}

std::vector<DirectedEdge> reversed(std::vector<DirectedEdge> edges) {
    for (DirectedEdge& e : edges) std::swap(e.a, e.b);
    return edges;
}

// Each triangle as its corners (x, y, intensity), turned to start at its least corner (the
// winding kept), the list sorted: equal for the same triangles in any order.
using Corner = std::tuple<double, double, float>;
std::vector<std::array<Corner, 3>> triangles(const ShadowMesh& m) {
    std::vector<std::array<Corner, 3>> out;
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        std::array<Corner, 3> t;
        for (int k = 0; k < 3; ++k) {
            const ShadowVertex& v = m.vertices[m.indices[i + size_t(k)]];
            t[size_t(k)] = {v.x, v.y, v.intensity};
        }
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<size_t> partSizes(std::span<const DirectedEdge> edges) {
    std::vector<size_t> sizes;
    for (const auto& p : separateShadowParts(edges)) sizes.push_back(p.size());
    std::sort(sizes.begin(), sizes.end());
    return sizes;
}

}  // namespace

TEST(PlanarShadowParts, ShadowsThatDoNotMeetArePartsAndShadowsThatMeetAreOne) {
    EXPECT_EQ(partSizes(join({rectEdges(0, 0, 100000, 100000), rectEdges(300000, 0, 400000, 100000)})),
              (std::vector<size_t>{4, 4}));
    // Crossing, nested, touching at a corner, sharing a side: one part each.
    EXPECT_EQ(partSizes(join({rectEdges(0, 0, 100000, 100000), rectEdges(50000, 50000, 150000, 150000)})),
              (std::vector<size_t>{8}));
    EXPECT_EQ(partSizes(join({rectEdges(0, 0, 400000, 400000), rectEdges(100000, 100000, 200000, 200000)})),
              (std::vector<size_t>{8}));
    EXPECT_EQ(partSizes(join({rectEdges(0, 0, 100000, 100000), rectEdges(100000, 100000, 200000, 200000)})),
              (std::vector<size_t>{8}));
    EXPECT_EQ(partSizes(join({rectEdges(0, 0, 100000, 100000), rectEdges(100000, 0, 200000, 100000)})),
              (std::vector<size_t>{8}));
    // A shadow inside another's hole (winding 0 between them) is a part of its own; the ring
    // keeps its outer and inner sides together.
    EXPECT_EQ(partSizes(join({rectEdges(0, 0, 500000, 500000), reversed(rectEdges(100000, 100000, 400000, 400000)),
                              rectEdges(200000, 200000, 300000, 300000)})),
              (std::vector<size_t>{4, 8}));
    // Long thin shadows crossing without a shared vertex (a plus sign): one part.
    EXPECT_EQ(partSizes(join({rectEdges(0, 100000, 300000, 120000), rectEdges(140000, 0, 160000, 300000)})),
              (std::vector<size_t>{8}));
    EXPECT_TRUE(separateShadowParts({}).empty());
}

TEST(PlanarShadowParts, TheSplitDoesNotDependOnTheEdgesOrder) {
    std::vector<DirectedEdge> edges = join({rectEdges(0, 0, 100000, 100000), rectEdges(300000, 0, 400000, 100000),
                                            rectEdges(320000, 20000, 500000, 60000)});
    const auto parts = separateShadowParts(edges);
    ASSERT_EQ(parts.size(), 2u);
    EXPECT_TRUE(std::is_sorted(parts[0].begin(), parts[0].end(), edgeLess));
    std::mt19937 rng(7);
    for (int round = 0; round < 5; ++round) {
        std::shuffle(edges.begin(), edges.end(), rng);
        const auto again = separateShadowParts(edges);
        ASSERT_EQ(again.size(), parts.size());
        for (size_t i = 0; i < parts.size(); ++i) EXPECT_TRUE(sameEdges(again[i], parts[i])) << i;
    }
}

// Soft shadows of three squares from n light samples (each sample shifts every square), one pair
// of them overlapping: the fill of each part alone, all put together, is the whole fill's set of
// triangles with the same intensities.
TEST(PlanarShadowParts, FillingThePartsApartGivesTheWholeFill) {
    const int n = 8;
    std::vector<std::vector<DirectedEdge>> outlines;
    std::mt19937 rng(3);
    std::uniform_int_distribution<int64_t> jitter(-9000, 9000);
    for (int s = 0; s < n; ++s) {
        int64_t dx = jitter(rng), dy = jitter(rng);
        outlines.push_back(hardOutline(join({rectEdges(dx, dy, 100000 + dx, 80000 + dy),
                                             rectEdges(60000 + dx, 50000 + dy, 140000 + dx, 160000 + dy),
                                             rectEdges(300000 + dx, 30000 + dy, 380000 + dx, 90000 + dy)})));
    }
    const std::vector<DirectedEdge> merged = mergeOutlines(outlines);
    const auto parts = separateShadowParts(merged);
    ASSERT_EQ(parts.size(), 2u);
    for (FillMode mode : {FillMode::Smooth, FillMode::Steps, FillMode::Rings}) {
        SCOPED_TRACE(int(mode));
        const ShadowMesh whole = fillShadow(merged, n, mode);
        ShadowMesh apart;
        double shadowArea = 0, umbraArea = 0;
        for (const auto& part : parts) {
            ShadowMesh m = fillShadow(part, n, mode);
            shadowArea += m.shadowArea;
            umbraArea += m.umbraArea;
            const uint32_t base = uint32_t(apart.vertices.size());
            apart.vertices.insert(apart.vertices.end(), m.vertices.begin(), m.vertices.end());
            for (uint32_t i : m.indices) apart.indices.push_back(base + i);
        }
        EXPECT_NEAR(shadowArea, whole.shadowArea, 1e-9 * whole.shadowArea);
        EXPECT_NEAR(umbraArea, whole.umbraArea, 1e-9 * whole.shadowArea);
        EXPECT_GT(whole.umbraArea, 0.0);
        EXPECT_EQ(triangles(apart), triangles(whole));
    }
}
