// How trapezoids are read from the sweep's slabs and merged along runs of the same segments.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/trapezoids.h"

#include <utility>


namespace ss::planar {

TrapezoidCollector::TrapezoidCollector(std::span<const SweepSegment> segments, RegionFn inside)
    : segments_(segments), inside_(std::move(inside)), open_(segments.size()) {}

void TrapezoidCollector::emit(Open& o) {
    const ISeg& b = segments_[o.bottom].seg;
    const ISeg& t = segments_[o.top].seg;
    Trapezoid z;
    z.x0 = o.x0.toDouble();
    z.x1 = o.x1.toDouble();
    z.yBottom0 = yAt(b, o.x0).toDouble();
    z.yBottom1 = yAt(b, o.x1).toDouble();
    z.yTop0 = yAt(t, o.x0).toDouble();
    z.yTop1 = yAt(t, o.x1).toDouble();
    z.winding = o.winding;
    z.windingBelow = o.below;
    z.windingAbove = o.above;
    z.bottomSeg = o.bottom;
    z.topSeg = o.top;
    z.rx0 = o.x0;
    z.rx1 = o.x1;
    out_.push_back(z);
    o.bottom = -1;
}

void TrapezoidCollector::onSlab(const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups) {
    ++slab_;
    // A trapezoid extended in the last slab can go on only when this slab starts where that one
    // ended (the sweep leaves a gap where no segment is active).
    const bool touchesLast = slab_ > 1 && compareX(lastXr_, xl) == 0;
    lastXr_ = xr;
    // Coincident edges that cancel (delta 0) change nothing: trapezoids span across them.
    live_.clear();
    for (const SlabGroup& g : groups)
        if (g.delta != 0) live_.push_back(g);
    nextList_.clear();
    int w = 0;
    for (size_t i = 0; i + 1 < live_.size(); ++i) {
        int below = w;
        w += live_[i].delta;
        if (!inside_(w)) continue;
        int above = w + live_[i + 1].delta;
        int bottom = live_[i].seg, top = live_[i + 1].seg;
        Open& o = open_[bottom];
        // Slabs with the same sides and windings merge into one trapezoid.
        bool extends = touchesLast && o.bottom == bottom && o.slab == slab_ - 1 && o.top == top &&
                       o.winding == w && o.below == below && o.above == above;
        if (extends) {
            o.x1 = xr;
        } else {
            if (o.bottom >= 0) emit(o);
            o = Open{bottom, top, w, below, above, xl, xr, slab_};
        }
        o.slab = slab_;
        nextList_.push_back(bottom);
    }
    for (int b : openList_)
        if (open_[b].bottom >= 0 && open_[b].slab != slab_) emit(open_[b]);
    openList_.swap(nextList_);
}

std::vector<Trapezoid> TrapezoidCollector::finish() {
    for (int b : openList_)
        if (open_[b].bottom >= 0) emit(open_[b]);
    openList_.clear();
    return std::move(out_);
}

std::vector<Trapezoid> trapezoids(std::span<const SweepSegment> segments, const RegionFn& inside) {
    TrapezoidCollector c(segments, inside);
    sweep(segments, [&](const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups) { c.onSlab(xl, xr, groups); });
    return c.finish();
}

int triangulateCorners(const Trapezoid& t, int (*tris)[3]) {
    // Which vertical sides have length is decided exactly by the sweep order (bottom below top
    // in the slab), but the doubles may round equal: a side of zero length in doubles has no area.
    bool left = t.yTop0 > t.yBottom0, right = t.yTop1 > t.yBottom1;
    int n = 0;
    auto add = [&](int a, int b, int c) {
        tris[n][0] = a, tris[n][1] = b, tris[n][2] = c;
        ++n;
    };
    if (left && right) {
        add(0, 1, 2);
        add(0, 2, 3);
    } else if (left) {
        add(0, 1, 3);
    } else if (right) {
        add(0, 1, 2);
    }
    return n;
}

double cornerX(const Trapezoid& t, int corner) { return (corner == 0 || corner == 3) ? t.x0 : t.x1; }

double cornerY(const Trapezoid& t, int corner) {
    switch (corner) {
        case 0: return t.yBottom0;
        case 1: return t.yBottom1;
        case 2: return t.yTop1;
        default: return t.yTop0;
    }
}

void triangulate(const Trapezoid& t, std::vector<Triangle2>* out) {
    int tris[2][3];
    int n = triangulateCorners(t, tris);
    for (int i = 0; i < n; ++i) {
        Triangle2 tri;
        for (int k = 0; k < 3; ++k) {
            tri.x[k] = cornerX(t, tris[i][k]);
            tri.y[k] = cornerY(t, tris[i][k]);
        }
        out->push_back(tri);
    }
}

}  // namespace ss::planar
