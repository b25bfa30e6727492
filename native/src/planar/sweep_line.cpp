// How the sweep line orders the active segments, finds the next event and reports slabs.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/sweep_line.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

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
    // Coincident segments become one with their deltas summed, and those that cancel go: an open
    // mesh is projected face by face, so each interior edge arrives twice, in opposite directions.
    // Left in, such pairs tie at every event they span and the exact predicates decide each tie
    // (on a 16k-triangle open Suzanne 99% of all order tests; the hard outlines took 2 s).
    auto key = [](const SweepSegment& s) { return std::tie(s.seg.lo.x, s.seg.lo.y, s.seg.hi.x, s.seg.hi.y); };
    std::sort(out.begin(), out.end(), [&](const SweepSegment& a, const SweepSegment& b) { return key(a) < key(b); });
    size_t kept = 0;
    for (size_t i = 0; i < out.size();) {
        SweepSegment merged = out[i];
        size_t j = i + 1;
        for (; j < out.size() && key(out[j]) == key(merged); ++j) merged.delta += out[j].delta;
        if (merged.delta != 0) out[kept++] = merged;
        i = j;
    }
    out.resize(kept);
    return out;
}

namespace {

// Order just to the right of x: by y at x, then by slope. 0 means collinear here.
int orderAt(const ISeg& s, const ISeg& t, const RatX& x) {
    int c = compareAtX(s, t, x);
    return c != 0 ? c : compareSlope(s, t);
}

// The y of every active segment at the current x in doubles: most order decisions are far from
// a tie and need no exact arithmetic (same error bound as predicates.cpp's filters).
struct Filter {
    std::vector<double> slope, y;
    double eps(int a, int b) const { return 1e-7 * (1.0 + std::fabs(slope[a]) + std::fabs(slope[b])); }
    // -1 / +1 when the doubles decide, 0 when the exact predicate must.
    int order(int a, int b) const {
        double d = y[a] - y[b], e = eps(a, b);
        return d > e ? 1 : (d < -e ? -1 : 0);
    }
};

bool before(const SweepSegment* segs, const Filter& f, int a, int b, const RatX& x) {
    int c = f.order(a, b);
    if (c == 0) c = orderAt(segs[a].seg, segs[b].seg, x);
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
    Filter filter;
    filter.slope.resize(segments.size());
    filter.y.resize(segments.size());
    for (size_t i = 0; i < segments.size(); ++i)
        filter.slope[i] = double(segs[i].seg.dy()) / double(segs[i].seg.dx());
    size_t next = 0;
    if (byStart.empty()) return stats;
    RatX cur = RatX::of(segs[byStart[0]].seg.lo.x);
    for (;;) {
        ++stats.events;
        // Segments ending here leave; segments starting here join.
        const double curD = cur.toDouble();
        auto endsByCur = [&](int i) {
            double d = double(segs[i].seg.hi.x) - curD;
            if (d > 1e-7) return false;
            if (d < -1e-7) return true;
            return compareX(RatX::of(segs[i].seg.hi.x), cur) <= 0;
        };
        active.erase(std::remove_if(active.begin(), active.end(), endsByCur), active.end());
        while (next < byStart.size() && compareX(RatX::of(segs[byStart[next]].seg.lo.x), cur) <= 0)
            active.push_back(byStart[next++]);
        if (active.empty()) {
            if (next == byStart.size()) break;
            cur = RatX::of(segs[byStart[next]].seg.lo.x);
            continue;
        }
        for (int i : active)
            filter.y[i] = double(segs[i].seg.lo.y) + (curD - double(segs[i].seg.lo.x)) * filter.slope[i];
        // Insertion sort: the order just right of the previous event is nearly the order here.
        for (size_t i = 1; i < active.size(); ++i) {
            int v = active[i];
            size_t j = i;
            while (j > 0 && before(segs, filter, v, active[j - 1], cur)) {
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
        // Every active segment ends after cur: the nearest end is the smallest integer hi.x.
        int64_t nearest = segs[active[0]].seg.hi.x;
        for (int i : active) nearest = std::min(nearest, segs[i].seg.hi.x);
        if (next < byStart.size()) nearest = std::min(nearest, segs[byStart[next]].seg.lo.x);
        offer(RatX::of(nearest));
        groups.clear();
        for (size_t i = 0; i < active.size(); ++i) {
            const ISeg& s = segs[active[i]].seg;
            if (!groups.empty() && filter.order(groups.back().seg, active[i]) == 0 &&
                orderAt(segs[groups.back().seg].seg, s, cur) == 0) {
                groups.back().delta += segs[active[i]].delta;
                continue;
            }
            if (!groups.empty()) {
                const ISeg& below = segs[groups.back().seg].seg;
                // Cheap rejection first: a crossing well before cur or well after the slab's
                // current end cannot end the slab.
                double ax = approxCrossingX(below, s);
                bool maybe = !std::isnan(ax) && ax > curD - 1e-3 && (!haveEnd || ax < end.toDouble() + 1e-3);
                RatX x;
                if (maybe && crossingX(below, s, &x) && compareX(x, cur) > 0) offer(x);
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
