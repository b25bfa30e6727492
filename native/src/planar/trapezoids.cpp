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
        out.push_back(z);
    };
    std::unordered_map<uint64_t, Open> open, next;
    sweep(segments, [&](const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups) {
        next.clear();
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

void triangulate(const Trapezoid& t, std::vector<Triangle2>* out) {
    bool left = t.yTop0 > t.yBottom0, right = t.yTop1 > t.yBottom1;
    if (left && right) {
        out->push_back({{t.x0, t.x1, t.x1}, {t.yBottom0, t.yBottom1, t.yTop1}});
        out->push_back({{t.x0, t.x1, t.x0}, {t.yBottom0, t.yTop1, t.yTop0}});
    } else if (left) {
        out->push_back({{t.x0, t.x1, t.x0}, {t.yBottom0, t.yBottom1, t.yTop0}});
    } else if (right) {
        out->push_back({{t.x0, t.x1, t.x1}, {t.yBottom0, t.yBottom1, t.yTop1}});
    }
}

}  // namespace ss::planar
