// How the sweep line orders the active segments, finds the next event and reports slabs.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/sweep_line.h"

#include <algorithm>
#include <numeric>

namespace ss::planar {

std::vector<SweepSegment> toSweepSegments(std::span<const DirectedEdge> edges) {
    std::vector<SweepSegment> out;
    out.reserve(edges.size());
    for (const DirectedEdge& e : edges) {
        if (e.a.x == e.b.x || e.weight == 0) continue;
        SweepSegment s;
        // Shadow on the right: walking +x the shadow is below, so crossing upward leaves it.
        if (e.a.x < e.b.x) {
            s.seg = ISeg{e.a, e.b};
            s.delta = -e.weight;
        } else {
            s.seg = ISeg{e.b, e.a};
            s.delta = e.weight;
        }
        out.push_back(s);
    }
    return out;
}

namespace {

// Order just to the right of x: by y at x, then by slope. 0 means collinear here.
int orderAt(const ISeg& s, const ISeg& t, const RatX& x) {
    int c = compareAtX(s, t, x);
    return c != 0 ? c : compareSlope(s, t);
}

bool before(const SweepSegment* segs, int a, int b, const RatX& x) {
    int c = orderAt(segs[a].seg, segs[b].seg, x);
    return c != 0 ? c < 0 : a < b;
}

}  // namespace

SweepStats sweep(std::span<const SweepSegment> segments, const SlabFn& onSlab) {
    SweepStats stats;
    const SweepSegment* segs = segments.data();
    std::vector<int> byStart(segments.size());
    std::iota(byStart.begin(), byStart.end(), 0);
    std::sort(byStart.begin(), byStart.end(),
              [&](int a, int b) { return segs[a].seg.lo.x < segs[b].seg.lo.x; });

    std::vector<int> active;
    std::vector<SlabGroup> groups;
    size_t next = 0;
    if (byStart.empty()) return stats;
    RatX cur = RatX::of(segs[byStart[0]].seg.lo.x);
    for (;;) {
        ++stats.events;
        // Segments ending here leave; segments starting here join.
        active.erase(std::remove_if(active.begin(), active.end(),
                                    [&](int i) { return compareX(RatX::of(segs[i].seg.hi.x), cur) <= 0; }),
                     active.end());
        while (next < byStart.size() && compareX(RatX::of(segs[byStart[next]].seg.lo.x), cur) <= 0)
            active.push_back(byStart[next++]);
        if (active.empty()) {
            if (next == byStart.size()) break;
            cur = RatX::of(segs[byStart[next]].seg.lo.x);
            continue;
        }
        // Insertion sort: the order just right of the previous event is nearly the order here.
        for (size_t i = 1; i < active.size(); ++i) {
            int v = active[i];
            size_t j = i;
            while (j > 0 && before(segs, v, active[j - 1], cur)) {
                active[j] = active[j - 1];
                --j;
            }
            active[j] = v;
        }
        // The slab ends at the nearest start, end, or crossing of two neighbours after cur.
        RatX end{};
        bool haveEnd = false;
        auto offer = [&](const RatX& x) {
            if (compareX(x, cur) > 0 && (!haveEnd || compareX(x, end) < 0)) {
                end = x;
                haveEnd = true;
            }
        };
        if (next < byStart.size()) offer(RatX::of(segs[byStart[next]].seg.lo.x));
        for (int i : active) offer(RatX::of(segs[i].seg.hi.x));
        groups.clear();
        for (size_t i = 0; i < active.size(); ++i) {
            const ISeg& s = segs[active[i]].seg;
            if (!groups.empty() && orderAt(segs[groups.back().seg].seg, s, cur) == 0) {
                groups.back().delta += segs[active[i]].delta;
                continue;
            }
            if (!groups.empty()) {
                RatX x;
                if (crossingX(segs[groups.back().seg].seg, s, &x) && compareX(x, cur) > 0) {
                    offer(x);
                }
            }
            groups.push_back(SlabGroup{active[i], segs[active[i]].delta});
        }
        // Every active segment ends strictly after cur, so an end always exists.
        onSlab(cur, end, groups);
        cur = end;
    }
    return stats;
}

}  // namespace ss::planar
