// Does the planar sweep find the exact hard-shadow outline and tile it with trapezoids, on
// named degenerate fixtures and on randomised triangle sets checked against Clipper?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>
#include <polyclipping/clipper.hpp>

#include <cmath>
#include <cstdlib>
#include <random>

#include "planar/outline.h"
#include "planar/snap.h"
#include "planar/trapezoids.h"

using namespace ss::planar;

namespace {

// A triangle as directed edges with the shadow on the right (clockwise).
void addTriangle(IPoint a, IPoint b, IPoint c, std::vector<DirectedEdge>* out) {
    if (orient(a, b, c) > 0) std::swap(b, c);
    out->push_back({a, b, 1});
    out->push_back({b, c, 1});
    out->push_back({c, a, 1});
}

void addPolygon(const std::vector<IPoint>& p, std::vector<DirectedEdge>* out) {
    for (size_t i = 0; i < p.size(); ++i) out->push_back({p[i], p[(i + 1) % p.size()], 1});
}

// Clockwise axis-aligned rectangle (shadow inside); counter-clockwise makes a hole.
std::vector<IPoint> rect(int64_t x0, int64_t y0, int64_t x1, int64_t y1, bool hole = false) {
    std::vector<IPoint> r = {{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}};
    if (hole) std::reverse(r.begin(), r.end());
    return r;
}

struct Result {
    double outlineArea = 0;     // from the linked chains
    double trapezoidArea = 0;   // sum over the triangulation
    size_t chains = 0, holes = 0;
};

Result run(const std::vector<DirectedEdge>& edges) {
    Result r;
    std::vector<DirectedEdge> outline = hardOutline(edges);
    std::vector<Chain> chains = linkChains(outline);
    r.outlineArea = regionArea(chains);
    r.chains = chains.size();
    for (const Chain& c : chains)
        if (twiceSignedArea(c) > 0) ++r.holes;
    std::vector<SweepSegment> segs = toSweepSegments(edges);
    for (const Trapezoid& t : trapezoids(segs, [](int w) { return w >= 1; })) r.trapezoidArea += t.area();
    return r;
}

// The independent answer: Clipper's non-zero union of the same closed paths.
double clipperUnionArea(const std::vector<std::vector<IPoint>>& paths) {
    ClipperLib::Paths in;
    for (const auto& p : paths) {
        ClipperLib::Path q;
        for (const IPoint& v : p) q.push_back(ClipperLib::IntPoint(v.x, v.y));
        in.push_back(q);
    }
    ClipperLib::Clipper c;
    c.AddPaths(in, ClipperLib::ptSubject, true);
    ClipperLib::Paths out;
    c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    double a = 0;
    for (const auto& p : out) a += ClipperLib::Area(p);
    return std::fabs(a);
}

}  // namespace

TEST(PlanarOutline, SquareAreaAndOneClockwiseChain) {
    std::vector<DirectedEdge> e;
    addPolygon(rect(0, 0, 100, 50), &e);
    Result r = run(e);
    EXPECT_EQ(r.outlineArea, 5000.0);
    EXPECT_EQ(r.trapezoidArea, 5000.0);
    EXPECT_EQ(r.chains, 1u);
    EXPECT_EQ(r.holes, 0u);
}

TEST(PlanarOutline, CounterClockwiseAloneIsNoShadow) {
    // Winding -1 is not shadow: an inside-out polygon alone casts nothing.
    std::vector<DirectedEdge> e;
    addPolygon(rect(0, 0, 100, 50, true), &e);
    EXPECT_EQ(run(e).outlineArea, 0.0);
}

TEST(PlanarOutline, HoleIsKept) {
    std::vector<DirectedEdge> e;
    addPolygon(rect(0, 0, 100, 100), &e);
    addPolygon(rect(25, 25, 75, 75, true), &e);
    Result r = run(e);
    EXPECT_EQ(r.outlineArea, 10000.0 - 2500.0);
    EXPECT_EQ(r.trapezoidArea, 7500.0);
    EXPECT_EQ(r.chains, 2u);
    EXPECT_EQ(r.holes, 1u);
}

TEST(PlanarOutline, DuplicateAndCollinearEdges) {
    // The same triangle twice (winding 2), and two squares sharing an edge (edges cancel).
    std::vector<DirectedEdge> e;
    addTriangle({0, 0}, {100, 0}, {0, 100}, &e);
    addTriangle({0, 0}, {100, 0}, {0, 100}, &e);
    addPolygon(rect(200, 0, 300, 100), &e);
    addPolygon(rect(300, 0, 400, 100), &e);
    addPolygon(rect(250, 100, 350, 200), &e);  // collinear with the shared top edge
    Result r = run(e);
    EXPECT_EQ(r.outlineArea, 5000.0 + 20000.0 + 10000.0);
    EXPECT_EQ(r.trapezoidArea, r.outlineArea);
}

TEST(PlanarOutline, EdgesMeetingAtAVertex) {
    // Two triangles touching only at (50, 50), plus a fan of triangles around one vertex.
    std::vector<DirectedEdge> e;
    addTriangle({0, 0}, {50, 50}, {0, 100}, &e);
    addTriangle({100, 0}, {50, 50}, {100, 100}, &e);
    for (int k = 0; k < 6; ++k) {
        double a0 = k * M_PI / 3, a1 = (k + 1) * M_PI / 3;
        addTriangle({500, 500}, {500 + int64_t(std::lround(100 * std::cos(a0))), 500 + int64_t(std::lround(100 * std::sin(a0)))},
                    {500 + int64_t(std::lround(100 * std::cos(a1))), 500 + int64_t(std::lround(100 * std::sin(a1)))}, &e);
    }
    Result r = run(e);
    std::vector<std::vector<IPoint>> paths;
    for (size_t i = 0; i < e.size(); i += 3) paths.push_back({e[i].a, e[i + 1].a, e[i + 2].a});
    double expect = clipperUnionArea(paths);
    EXPECT_NEAR(r.outlineArea, expect, 1e-9 * expect);
    EXPECT_NEAR(r.trapezoidArea, expect, 1e-9 * expect);
}

TEST(PlanarOutline, TouchingHoles) {
    // Two holes sharing an edge and a third touching them at a corner.
    std::vector<DirectedEdge> e;
    addPolygon(rect(0, 0, 300, 300), &e);
    addPolygon(rect(50, 50, 150, 150, true), &e);
    addPolygon(rect(150, 50, 250, 150, true), &e);
    addPolygon(rect(250, 150, 280, 280, true), &e);
    Result r = run(e);
    EXPECT_EQ(r.outlineArea, 90000.0 - 20000.0 - 3900.0);
    EXPECT_EQ(r.trapezoidArea, r.outlineArea);
}

TEST(PlanarOutline, Slivers) {
    // A triangle one grid unit thick and 2^21 long, crossed by another sliver.
    std::vector<DirectedEdge> e;
    const int64_t L = kGridLimit;
    addTriangle({-L, 0}, {L, 1}, {L, -1}, &e);
    addTriangle({0, -L}, {1, L}, {-1, L}, &e);
    Result r = run(e);
    std::vector<std::vector<IPoint>> paths = {{{-L, 0}, {L, 1}, {L, -1}}, {{0, -L}, {1, L}, {-1, L}}};
    double expect = clipperUnionArea(paths);
    // Crossing points are rounded to the grid: each moves the outline by < 1 unit along an
    // edge of length 2^21, so a few units^2 of 4e6 total.
    EXPECT_NEAR(r.trapezoidArea, expect, 4.0);
    EXPECT_NEAR(r.outlineArea, expect, 8.0);
}

TEST(PlanarOutline, HugeAndTinyPlaneCoordinates) {
    // Plane coordinates near 1e7 and near 1e-7: the snap scales the receiver box to the grid,
    // so both cases give the same grid outline and relative precision 2^-20.
    for (double unit : {1e7, 1e-7}) {
        Snap snap(1e7 * (unit > 1), 0.0, 2.0 * unit);
        std::vector<DirectedEdge> e;
        double cx = 1e7 * (unit > 1);
        double sq[4][2] = {{-1, -1}, {-1, 1}, {1, 1}, {1, -1}};  // clockwise square of side 2 units
        for (int k = 0; k < 4; ++k)
            snap.addEdge(cx + sq[k][0] * unit, sq[k][1] * unit, cx + sq[(k + 1) % 4][0] * unit,
                         sq[(k + 1) % 4][1] * unit, 1, &e);
        Result r = run(e);
        double planeArea = r.outlineArea / (snap.scale() * snap.scale());
        EXPECT_NEAR(planeArea, 4.0 * unit * unit, 4.0 * unit * unit * 1e-6) << "unit " << unit;
        EXPECT_EQ(r.chains, 1u);
    }
}

TEST(PlanarOutline, EdgesLeavingTheBoxKeepWindingInside) {
    // A huge triangle covering the whole box: clipped and clamped, its inside is the full box.
    Snap snap(0.0, 0.0, 1.0);
    std::vector<DirectedEdge> e;
    double t[3][2] = {{-1e6, -1e6}, {0, 3e6}, {1e6, -1e6}};  // clockwise
    for (int k = 0; k < 3; ++k) snap.addEdge(t[k][0], t[k][1], t[(k + 1) % 3][0], t[(k + 1) % 3][1], 1, &e);
    Result r = run(e);
    double L = double(kGridLimit);
    EXPECT_EQ(r.trapezoidArea, 4 * L * L);
}

// Property: random triangle sets, on a fine grid and on a coarse lattice that provokes
// collinear, duplicate and touching edges. Tolerance: each rounded crossing moves the outline
// by at most 0.71 grid units along its edges, so |error| <= 0.71 * perimeter * (1 for us + 1
// for Clipper, which also rounds); the trapezoid area is exact up to double rounding.
TEST(PlanarOutline, RandomTriangleSetsMatchClipperUnion) {
    std::mt19937 rng(1234);
    const int cases = std::getenv("SS_TEST_QUICK") ? 100 : 400;
    for (int c = 0; c < cases; ++c) {
        bool coarse = c % 2 == 1;
        int64_t span = coarse ? 8 : kGridLimit;
        int64_t unit = coarse ? kGridLimit / 8 : 1;
        std::uniform_int_distribution<int64_t> coord(-span, span);
        std::uniform_int_distribution<int> count(1, 14);
        int n = count(rng);
        std::vector<DirectedEdge> e;
        std::vector<std::vector<IPoint>> paths;
        double perimeter = 0;
        for (int i = 0; i < n; ++i) {
            IPoint a{coord(rng) * unit, coord(rng) * unit}, b{coord(rng) * unit, coord(rng) * unit},
                p{coord(rng) * unit, coord(rng) * unit};
            if (orient(a, b, p) == 0) continue;
            addTriangle(a, b, p, &e);
            paths.push_back({e[e.size() - 3].a, e[e.size() - 2].a, e[e.size() - 1].a});  // all clockwise
            for (size_t k = e.size() - 3; k < e.size(); ++k)
                perimeter += std::hypot(double(e[k].b.x - e[k].a.x), double(e[k].b.y - e[k].a.y));
        }
        Result r = run(e);
        double expect = clipperUnionArea(paths);
        double tol = 1.5 * perimeter + 1e-9 * expect;
        ASSERT_NEAR(r.trapezoidArea, expect, tol) << "case " << c;
        ASSERT_NEAR(r.outlineArea, expect, 2 * tol) << "case " << c;
    }
}

// Property: the triangulation covers the union exactly once. Random points: inside some
// input triangle <=> inside exactly one output triangle (points within 2 units of any edge are
// skipped, the rounding band).
TEST(PlanarOutline, TriangulationCoversOnceNoOverlap) {
    std::mt19937 rng(99);
    const int cases = std::getenv("SS_TEST_QUICK") ? 30 : 120;
    for (int c = 0; c < cases; ++c) {
        std::uniform_int_distribution<int64_t> coord(-1000, 1000);
        std::vector<DirectedEdge> e;
        std::vector<std::array<IPoint, 3>> tris;
        for (int i = 0; i < 8; ++i) {
            IPoint a{coord(rng), coord(rng)}, b{coord(rng), coord(rng)}, p{coord(rng), coord(rng)};
            if (orient(a, b, p) == 0) continue;
            addTriangle(a, b, p, &e);
            tris.push_back({a, b, p});
        }
        std::vector<Triangle2> out;
        for (const Trapezoid& t : trapezoids(toSweepSegments(e), [](int w) { return w >= 1; })) triangulate(t, &out);
        std::uniform_real_distribution<double> pc(-1000, 1000);
        for (int s = 0; s < 300; ++s) {
            double x = pc(rng), y = pc(rng);
            auto distToSeg = [&](double ax, double ay, double bx, double by) {
                double dx = bx - ax, dy = by - ay, t = ((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy);
                t = std::clamp(t, 0.0, 1.0);
                return std::hypot(x - ax - t * dx, y - ay - t * dy);
            };
            auto inTri = [&](const double* tx, const double* ty) {
                double s0 = (tx[1] - tx[0]) * (y - ty[0]) - (ty[1] - ty[0]) * (x - tx[0]);
                double s1 = (tx[2] - tx[1]) * (y - ty[1]) - (ty[2] - ty[1]) * (x - tx[1]);
                double s2 = (tx[0] - tx[2]) * (y - ty[2]) - (ty[0] - ty[2]) * (x - tx[2]);
                return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
            };
            bool nearEdge = false, inside = false;
            for (auto& t : tris) {
                double tx[3] = {double(t[0].x), double(t[1].x), double(t[2].x)};
                double ty[3] = {double(t[0].y), double(t[1].y), double(t[2].y)};
                for (int k = 0; k < 3; ++k)
                    nearEdge |= distToSeg(tx[k], ty[k], tx[(k + 1) % 3], ty[(k + 1) % 3]) < 2.0;
                inside |= inTri(tx, ty);
            }
            if (nearEdge) continue;
            int covered = 0;
            for (const Triangle2& t : out) covered += inTri(t.x, t.y);
            ASSERT_EQ(covered, inside ? 1 : 0) << "case " << c << " point " << x << "," << y;
        }
    }
}

namespace {

// Two triangles sharing an edge, as an open mesh arrives (face by face): the shared edge comes in
// both directions and must cancel, leaving the square's four sides; a repeated edge adds up.
TEST(SweepSegments, CoincidentEdgesMergeAndCancel) {
    std::vector<DirectedEdge> edges;
    addTriangle({0, 0}, {10, 0}, {10, 10}, &edges);
    addTriangle({0, 0}, {10, 10}, {0, 10}, &edges);
    std::vector<SweepSegment> segs = toSweepSegments(edges);
    // 6 edges: 2 vertical (dropped), the diagonal twice with opposite deltas (cancelled).
    ASSERT_EQ(segs.size(), 2u);
    for (const SweepSegment& s : segs) EXPECT_EQ(s.seg.dy(), 0);
    EXPECT_EQ(segs[0].delta + segs[1].delta, 0);
    EXPECT_NEAR(regionArea(linkChains(hardOutline(edges))), 100.0, 1e-9);

    std::vector<DirectedEdge> twice = {{{0, 0}, {10, 5}, 1}, {{0, 0}, {10, 5}, 1}};
    segs = toSweepSegments(twice);
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_EQ(std::abs(segs[0].delta), 2);
}

}  // namespace
