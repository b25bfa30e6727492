// How a winding-number region is cut into trapezoids (vertical sides, top and bottom on
// segments) and triangulated.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <span>
#include <vector>

#include "planar/outline.h"

namespace ss::planar {

// A trapezoid in grid coordinates; slabs with the same bottom and top segment are merged.
struct Trapezoid {
    double x0 = 0, x1 = 0;
    double yBottom0 = 0, yBottom1 = 0;  // bottom side at x0 and x1
    double yTop0 = 0, yTop1 = 0;        // top side at x0 and x1
    int winding = 0;                    // inside
    int windingBelow = 0;               // just below the bottom side
    int windingAbove = 0;               // just above the top side
    int bottomSeg = 0, topSeg = 0;      // representative segments of the two sides
    RatX rx0, rx1;                      // x0 and x1, exact
    double area() const { return 0.5 * (x1 - x0) * ((yTop0 - yBottom0) + (yTop1 - yBottom1)); }
};

std::vector<Trapezoid> trapezoids(std::span<const SweepSegment> segments, const RegionFn& inside);

// The same, fed slab by slab from a sweep someone else runs (so one sweep can serve several
// consumers).
class TrapezoidCollector {
public:
    TrapezoidCollector(std::span<const SweepSegment> segments, RegionFn inside);
    void onSlab(const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups);
    std::vector<Trapezoid> finish();

private:
    struct Open {
        int bottom = -1, top = -1, winding = 0, below = 0, above = 0;
        RatX x0, x1;
        size_t slab = 0;  // the last slab that extended it
    };
    void emit(Open& o);
    std::span<const SweepSegment> segments_;
    RegionFn inside_;
    std::vector<Trapezoid> out_;
    std::vector<Open> open_;  // one open trapezoid per bottom segment
    std::vector<int> openList_, nextList_;
    std::vector<SlabGroup> live_;
    size_t slab_ = 0;
    RatX lastXr_;  // where the last slab ended
};

// Corners: 0 bottom at x0, 1 bottom at x1, 2 top at x1, 3 top at x0. Two triangles per
// trapezoid (one when a vertical side has zero length), counter-clockwise, as corner triples.
int triangulateCorners(const Trapezoid& t, int (*tris)[3]);
double cornerX(const Trapezoid& t, int corner);
double cornerY(const Trapezoid& t, int corner);

struct Triangle2 {
    double x[3], y[3];
};
void triangulate(const Trapezoid& t, std::vector<Triangle2>* out);

}  // namespace ss::planar
