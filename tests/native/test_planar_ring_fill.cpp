// Does fill=rings tile the shadow exactly with triangles whose corners carry their ring's
// intensity, a crossing point the mean of its two rings, bays flat, and no overlaps?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "planar/outline.h"
#include "planar/ring_fill.h"
#include "planar/rings.h"
#include "test_planar_shapes.h"
#include "planar_oracles/level_rings.h"

using namespace ss::planar;
using ss::planar::test::rectEdges;

namespace {

std::vector<DirectedEdge> merge(const std::vector<std::vector<DirectedEdge>>& shapes) {
    std::vector<std::vector<DirectedEdge>> outlines;
    for (const auto& s : shapes) outlines.push_back(hardOutline(s));
    return mergeOutlines(outlines);
}

struct Hit {
    int triangles = 0;
    double value = -1;
};

// The triangles holding (x, y) (a point on no side) and the interpolated value in the last.
Hit sampleAt(const ShadowMesh& m, double x, double y) {
    Hit h;
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        const ShadowVertex& a = m.vertices[m.indices[i]];
        const ShadowVertex& b = m.vertices[m.indices[i + 1]];
        const ShadowVertex& c = m.vertices[m.indices[i + 2]];
        double d = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        double l1 = ((x - a.x) * (c.y - a.y) - (y - a.y) * (c.x - a.x)) / d;
        double l2 = ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)) / d;
        double l0 = 1 - l1 - l2;
        if (l0 > 0 && l1 > 0 && l2 > 0) {
            ++h.triangles;
            h.value = l0 * a.intensity + l1 * b.intensity + l2 * c.intensity;
        }
    }
    return h;
}

double triangleArea(const ShadowMesh& m, size_t i) {
    const ShadowVertex& a = m.vertices[m.indices[i]];
    const ShadowVertex& b = m.vertices[m.indices[i + 1]];
    const ShadowVertex& c = m.vertices[m.indices[i + 2]];
    return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

// Every triangle counter-clockwise, every corner in [0, 1], bays flat.
void expectWellFormed(const ShadowMesh& m) {
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        ASSERT_GT(triangleArea(m, i), 0.0) << "triangle " << i / 3;
        for (int k = 0; k < 3; ++k) {
            float v = m.vertices[m.indices[i + k]].intensity;
            ASSERT_GE(v, 0.0f);
            ASSERT_LE(v, 1.0f);
        }
    }
}

// The count field of axis-aligned rectangles, at a point inside none of their sides.
int countAt(const std::vector<std::array<int64_t, 4>>& rects, double x, double y) {
    int c = 0;
    for (const auto& r : rects) c += r[0] < x && x < r[2] && r[1] < y && y < r[3];
    return c;
}

}  // namespace

// Ring 1 the outer square, ring 2 the inner one: the strip between them is walked with
// triangles that all have corners on both rings (no bays), 0 on the outer and 1 on the inner
// ring; the strip and the umbra tile the outer square exactly, each point covered once.
TEST(PlanarRingFill, NestedSquaresStripIsWalkedBetweenTheRings) {
    std::vector<DirectedEdge> merged = merge({rectEdges(0, 0, 100, 100), rectEdges(30, 30, 70, 70)});
    RingFillStats stats;
    ShadowMesh m = fillRings(merged, 2, &stats);
    expectWellFormed(m);
    EXPECT_EQ(stats.fallbackStrips, 0u);
    EXPECT_EQ(stats.roundedStrips, 0u);
    EXPECT_EQ(stats.bayTriangles, 0u);
    EXPECT_EQ(stats.leakTriangles, 0u);
    EXPECT_EQ(stats.stripTriangles, 8u);  // 4 + 4 ring points, a closed band: 8 triangles
    EXPECT_EQ(m.shadowArea, 10000.0);
    EXPECT_EQ(m.umbraArea, 1600.0);
    for (const ShadowVertex& v : m.vertices) {
        bool outer = v.x == 0 || v.x == 100 || v.y == 0 || v.y == 100;
        bool inner = v.x >= 30 && v.x <= 70 && v.y >= 30 && v.y <= 70;
        ASSERT_TRUE(outer || inner);
        EXPECT_EQ(v.intensity, outer ? 0.0f : 1.0f) << v.x << "," << v.y;
    }
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 100.0);
    for (int i = 0; i < 2000; ++i) {
        double x = u(rng), y = u(rng);
        Hit h = sampleAt(m, x, y);
        ASSERT_EQ(h.triangles, 1) << x << "," << y;
        bool umbra = x > 30 && x < 70 && y > 30 && y < 70;
        if (umbra) {
            EXPECT_NEAR(h.value, 1.0, 1e-12);
        } else {
            EXPECT_TRUE(h.value >= 0.0 && h.value <= 1.0);
        }
    }
}

// Two squares crossing: A = [0,100]^2, B = [50,150]^2. Ring 1 is their union, ring 2 their
// intersection; the outlines cross at (100,50) and (50,100), which lie on both rings. The
// paper: an intersection point takes the mean of its two rings, 0.5 with two samples. The
// strip {count == 1} is two L shapes meeting only at those points.
TEST(PlanarRingFill, CrossingPointTakesTheMeanOfItsTwoRings) {
    std::vector<DirectedEdge> merged = merge({rectEdges(0, 0, 100, 100), rectEdges(50, 50, 150, 150)});
    RingFillStats stats;
    ShadowMesh m = fillRings(merged, 2, &stats);
    expectWellFormed(m);
    EXPECT_EQ(stats.fallbackStrips, 0u);
    EXPECT_EQ(stats.roundedStrips, 0u);
    EXPECT_EQ(stats.crossingVertices, 2u);
    EXPECT_EQ(m.shadowArea, 17500.0);
    EXPECT_EQ(m.umbraArea, 2500.0);
    int atCrossing = 0;
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        const ShadowVertex* c[3] = {&m.vertices[m.indices[i]], &m.vertices[m.indices[i + 1]],
                                    &m.vertices[m.indices[i + 2]]};
        bool umbra = c[0]->intensity == 1.0f && c[1]->intensity == 1.0f && c[2]->intensity == 1.0f;
        for (const ShadowVertex* v : c) {
            bool crossing = (v->x == 100 && v->y == 50) || (v->x == 50 && v->y == 100);
            bool inner = ((v->x == 50 || v->x == 100) && v->y >= 50 && v->y <= 100) ||
                         ((v->y == 50 || v->y == 100) && v->x >= 50 && v->x <= 100);
            if (umbra) continue;
            if (crossing) {
                EXPECT_EQ(v->intensity, 0.5f);
                ++atCrossing;
            } else {
                EXPECT_EQ(v->intensity, inner ? 1.0f : 0.0f) << v->x << "," << v->y;
            }
        }
    }
    EXPECT_GT(atCrossing, 0);
    std::vector<std::array<int64_t, 4>> rects = {{0, 0, 100, 100}, {50, 50, 150, 150}};
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 150.0);
    for (int i = 0; i < 2000; ++i) {
        double x = u(rng), y = u(rng);
        int count = countAt(rects, x, y);
        Hit h = sampleAt(m, x, y);
        ASSERT_EQ(h.triangles, count > 0 ? 1 : 0) << x << "," << y;
        if (count == 2) {
            EXPECT_NEAR(h.value, 1.0, 1e-12);
        }
    }
}

// Three samples: C = [-100,250]^2 holds A and B of the test above. Ring 2 is now A u B and
// ring 3 A n B; the crossing points lie on rings 2 and 3 and take (1/2 + 1)/2 = 0.75 in the
// strip between them, while in the strip between rings 1 and 2 they are ring 2's corners, 0.5.
TEST(PlanarRingFill, CrossingPointMeanDependsOnTheStrip) {
    std::vector<DirectedEdge> merged =
        merge({rectEdges(-100, -100, 250, 250), rectEdges(0, 0, 100, 100), rectEdges(50, 50, 150, 150)});
    RingFillStats stats;
    ShadowMesh m = fillRings(merged, 3, &stats);
    expectWellFormed(m);
    EXPECT_EQ(stats.fallbackStrips, 0u);
    std::vector<std::array<int64_t, 4>> rects = {{-100, -100, 250, 250}, {0, 0, 100, 100}, {50, 50, 150, 150}};
    std::map<int, std::vector<float>> crossingValues;  // strip count -> values at the crossings
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        const ShadowVertex* c[3] = {&m.vertices[m.indices[i]], &m.vertices[m.indices[i + 1]],
                                    &m.vertices[m.indices[i + 2]]};
        int count = countAt(rects, (c[0]->x + c[1]->x + c[2]->x) / 3, (c[0]->y + c[1]->y + c[2]->y) / 3);
        for (const ShadowVertex* v : c)
            if ((v->x == 100 && v->y == 50) || (v->x == 50 && v->y == 100)) crossingValues[count].push_back(v->intensity);
    }
    ASSERT_FALSE(crossingValues[1].empty());
    ASSERT_FALSE(crossingValues[2].empty());
    for (float v : crossingValues[1]) EXPECT_EQ(v, 0.5f);
    for (float v : crossingValues[2]) EXPECT_EQ(v, 0.75f);
    EXPECT_EQ(m.shadowArea, 350.0 * 350.0);
    EXPECT_EQ(m.umbraArea, 2500.0);
    // The same areas as the level-set rings (planar::buildRings, the rings' definition).
    std::vector<Ring> levels = buildRings(merged, 3);
    EXPECT_EQ(m.shadowArea, regionArea(levels[0].chains));
    EXPECT_EQ(m.umbraArea, regionArea(levels[2].chains));
}

// Random occluders (triangle soups shifted per sample, as in PlanarRings): the ring fill covers
// exactly the union (area equal to the trapezoid fill's, every point once), its umbra is the
// intersection, bays are flat, and inside the strip {count == c} every value lies between
// ring c's and ring c+1's intensities.
TEST(PlanarRingFill, RandomSamplesTileTheShadowBetweenTheirRings) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<int64_t> coord(-5000, 5000), shift(-600, 600);
    size_t strips = 0, bays = 0, fallbacks = 0, rounded = 0;
    for (int c = 0; c < 12; ++c) {
        const int n = 2 + c % 6;
        std::vector<std::array<IPoint, 3>> base;
        for (int t = 0; t < 4; ++t) {
            std::array<IPoint, 3> tri;
            for (IPoint& p : tri) p = IPoint{coord(rng), coord(rng)};
            if (orient(tri[0], tri[1], tri[2]) == 0) continue;
            if (orient(tri[0], tri[1], tri[2]) > 0) std::swap(tri[1], tri[2]);
            base.push_back(tri);
        }
        std::vector<std::vector<DirectedEdge>> shapes;
        for (int s = 0; s < n; ++s) {
            int64_t dx = shift(rng), dy = shift(rng);
            std::vector<DirectedEdge> e;
            for (auto& t : base)
                for (int k = 0; k < 3; ++k)
                    e.push_back({{t[k].x + dx, t[k].y + dy}, {t[(k + 1) % 3].x + dx, t[(k + 1) % 3].y + dy}, 1});
            shapes.push_back(e);
        }
        std::vector<DirectedEdge> merged = merge(shapes);
        RingFillStats stats;
        ShadowMesh rings = fillRings(merged, n, &stats);
        ShadowMesh steps = fillShadow(merged, n, FillMode::Steps);
        expectWellFormed(rings);
        strips += stats.stripTriangles;
        bays += stats.bayTriangles;
        fallbacks += stats.fallbackStrips;
        // The rings' crossing points are rounded (< 0.71 units), the trapezoids' are exact.
        double perimeter = 0;
        for (const DirectedEdge& e : merged) perimeter += std::hypot(double(e.b.x - e.a.x), double(e.b.y - e.a.y));
        EXPECT_NEAR(rings.shadowArea, steps.shadowArea, 0.71 * perimeter) << "case " << c;
        EXPECT_NEAR(rings.umbraArea, steps.umbraArea, 0.71 * perimeter) << "case " << c;
        double sum = 0;
        for (size_t i = 0; i < rings.indices.size(); i += 3) sum += triangleArea(rings, i);
        // The triangles tile the strips exactly, up to a grid-unit sliver where rounded chains cross.
        EXPECT_NEAR(sum, rings.shadowArea, stats.roundedStrips == 0 ? 1e-9 * rings.shadowArea : 0.71 * perimeter)
            << "case " << c;
        rounded += stats.roundedStrips;
        std::uniform_real_distribution<double> u(-5700.0, 5700.0);
        int misses = 0, samples = 0;
        for (int i = 0; i < 400; ++i) {
            double x = u(rng), y = u(rng);
            Hit s = sampleAt(steps, x, y);
            Hit r = sampleAt(rings, x, y);
            ASSERT_LE(r.triangles, 1) << "case " << c << " at " << x << "," << y;  // no overlaps
            if (s.triangles == 0 && r.triangles == 0) continue;
            ++samples;
            // Crossing points are rounded to the grid in the rings, not in the trapezoids: a
            // point within a unit of one may fall on different sides.
            if (r.triangles != s.triangles) {
                ++misses;
                continue;
            }
            int count = int(std::lround(s.value * n));
            EXPECT_GE(r.value, ringIntensity(count, n) - 1e-6) << "case " << c;
            EXPECT_LE(r.value, std::min(1.0f, ringIntensity(count + 1, n)) + 1e-6) << "case " << c;
        }
        EXPECT_LE(misses, std::max(1, samples / 100)) << "case " << c;
    }
    std::printf("strip triangles %zu, bays %zu, strips tiled up to a sliver %zu, fallback strips %zu\n", strips, bays,
                rounded, fallbacks);
    EXPECT_EQ(fallbacks, 0u);
    EXPECT_GT(strips, bays);
}
