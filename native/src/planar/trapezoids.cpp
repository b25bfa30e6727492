// How trapezoids are read from the sweep's slabs and merged along runs of the same segments.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/trapezoids.h"

#include <unordered_map>

namespace ss::planar {

namespace {
struct Open {
    int bottom, top, winding, below, above;
    RatX x0, x1;
};
uint64_t key(int bottom, int top) { return (uint64_t(uint32_t(bottom)) << 32) | uint32_t(top); }
}  // namespace

std::vector<Trapezoid> trapezoids(std::span<const SweepSegment> segments, const RegionFn& inside) {
    std::vector<Trapezoid> out;
    auto emit = [&](const Open& o) {
        const ISeg& b = segments[o.bottom].seg;
        const ISeg& t = segments[o.top].seg;
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
        out.push_back(z);
    };
    std::unordered_map<uint64_t, Open> open, next;
    std::vector<SlabGroup> live;
    sweep(segments, [&](const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups) {
        next.clear();
        // Coincident edges that cancel (delta 0) change nothing: trapezoids span across them.
        live.clear();
        for (const SlabGroup& g : groups)
            if (g.delta != 0) live.push_back(g);
        groups = live;
        int w = 0;
        for (size_t i = 0; i + 1 < groups.size(); ++i) {
            int below = w;
            w += groups[i].delta;
            if (!inside(w)) continue;
            int above = w + groups[i + 1].delta;
            Open o{groups[i].seg, groups[i + 1].seg, w, below, above, xl, xr};
            auto it = open.find(key(o.bottom, o.top));
            if (it != open.end() && it->second.winding == w && it->second.below == below &&
                it->second.above == above && compareX(it->second.x1, xl) == 0) {
                o.x0 = it->second.x0;
                open.erase(it);
            }
            next.emplace(key(o.bottom, o.top), o);
        }
        for (auto& [k, o] : open) emit(o);
        open.swap(next);
    });
    for (auto& [k, o] : open) emit(o);
    return out;
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
