// How region boundaries are collected from the sweep's slabs and linked into closed chains.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/outline.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace ss::planar {

namespace {

struct Pending {
    bool open = false;
    bool regionBelow = false;
    RatX x0, x1;
};

IPoint roundPoint(const ISeg& s, const RatX& x) {
    RatY y = yAt(s, x);
    return IPoint{roundDiv(x.p, x.q), roundDiv(y.num, y.den)};
}

}  // namespace

std::vector<DirectedEdge> regionBoundary(std::span<const SweepSegment> segments, const RegionFn& inside) {
    std::vector<DirectedEdge> out;
    std::vector<Pending> pending(segments.size());
    auto flush = [&](int seg) {
        Pending& p = pending[seg];
        if (!p.open) return;
        p.open = false;
        IPoint a = roundPoint(segments[seg].seg, p.x0), b = roundPoint(segments[seg].seg, p.x1);
        if (a == b) return;
        // Region below a left-to-right piece means it lies on the piece's right.
        out.push_back(p.regionBelow ? DirectedEdge{a, b, 1} : DirectedEdge{b, a, 1});
    };
    sweep(segments, [&](const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups) {
        int w = 0;
        for (const SlabGroup& g : groups) {
            bool below = inside(w), above = inside(w + g.delta);
            w += g.delta;
            if (below == above) continue;
            Pending& p = pending[g.seg];
            if (p.open && p.regionBelow == below && compareX(p.x1, xl) == 0) {
                p.x1 = xr;
                continue;
            }
            flush(g.seg);
            p = Pending{true, below, xl, xr};
        }
    });
    for (size_t i = 0; i < segments.size(); ++i) flush(int(i));
    return out;
}

namespace {
bool lessPoint(const IPoint& a, const IPoint& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; }
}  // namespace

void addVerticalConnectors(std::vector<DirectedEdge>* boundary) {
    std::map<IPoint, int, decltype(&lessPoint)> balance(&lessPoint);
    for (const DirectedEdge& e : *boundary) {
        balance[e.a] += e.weight;
        balance[e.b] -= e.weight;
    }
    IPoint prev{};
    int running = 0;
    bool havePrev = false;
    for (const auto& [p, b] : balance) {
        if (b == 0) continue;
        if (!havePrev || prev.x != p.x) running = 0;
        // running > 0: the points below send out more than they receive, so edges come down.
        if (running > 0) boundary->push_back(DirectedEdge{p, prev, running});
        if (running < 0) boundary->push_back(DirectedEdge{prev, p, -running});
        running += b;
        prev = p;
        havePrev = true;
    }
}

std::vector<Chain> linkChains(std::span<const DirectedEdge> boundaryIn, bool keepStraight) {
    auto less = &lessPoint;
    std::vector<DirectedEdge> boundary(boundaryIn.begin(), boundaryIn.end());
    addVerticalConnectors(&boundary);
    std::vector<std::pair<IPoint, IPoint>> edges;
    for (const DirectedEdge& e : boundary)
        for (int k = 0; k < std::abs(e.weight); ++k)
            edges.push_back(e.weight > 0 ? std::make_pair(e.a, e.b) : std::make_pair(e.b, e.a));

    std::map<IPoint, std::vector<int>, decltype(less)> outgoing(less);
    for (size_t i = 0; i < edges.size(); ++i) outgoing[edges[i].first].push_back(int(i));
    std::vector<bool> used(edges.size(), false);
    std::vector<Chain> chains;
    for (size_t start = 0; start < edges.size(); ++start) {
        if (used[start]) continue;
        Chain chain;
        size_t e = start;
        for (;;) {
            used[e] = true;
            chain.push_back(edges[e].first);
            const IPoint from = edges[e].first, at = edges[e].second;
            if (at == edges[start].first) break;
            // Where the boundary meets itself (two rings touching at a crossing), continue
            // along the first outgoing edge counter-clockwise from the way in: the region on
            // the right then lies in one wedge per visit, so the chain touches itself there
            // without crossing (a polygon a triangulation can walk).
            const double back = std::atan2(double(from.y - at.y), double(from.x - at.x));
            int best = -1;
            double bestTurn = 0;
            for (int o : outgoing[at]) {
                if (used[size_t(o)]) continue;
                const IPoint& to = edges[size_t(o)].second;
                double turn = std::fmod(std::atan2(double(to.y - at.y), double(to.x - at.x)) - back + 4.0 * M_PI, 2.0 * M_PI);
                if (turn == 0.0) turn = 2.0 * M_PI;
                if (best < 0 || turn < bestTurn) {
                    best = o;
                    bestTurn = turn;
                }
            }
            if (best < 0) break;  // cannot happen when every balance is zero
            e = size_t(best);
        }
        if (keepStraight) {
            if (chain.size() >= 3) chains.push_back(std::move(chain));
            continue;
        }
        // Drop vertices where the chain goes straight on.
        Chain simple;
        for (size_t i = 0; i < chain.size(); ++i) {
            const IPoint& a = chain[(i + chain.size() - 1) % chain.size()];
            const IPoint& b = chain[i];
            const IPoint& c = chain[(i + 1) % chain.size()];
            bool straight = orient(a, b, c) == 0 && (i128(b.x - a.x) * (c.x - b.x) + i128(b.y - a.y) * (c.y - b.y)) > 0;
            if (!straight) simple.push_back(b);
        }
        if (simple.size() >= 3) chains.push_back(std::move(simple));
    }
    return chains;
}

i128 twiceSignedArea(const Chain& chain) {
    i128 sum = 0;
    for (size_t i = 0; i < chain.size(); ++i) {
        const IPoint& a = chain[i];
        const IPoint& b = chain[(i + 1) % chain.size()];
        sum += i128(a.x) * b.y - i128(b.x) * a.y;
    }
    return sum;
}

double regionArea(std::span<const Chain> chains) {
    i128 sum = 0;
    for (const Chain& c : chains) sum += twiceSignedArea(c);
    return -double(sum) / 2.0;
}

std::vector<DirectedEdge> hardOutline(std::span<const DirectedEdge> projected) {
    std::vector<SweepSegment> segs = toSweepSegments(projected);
    std::vector<DirectedEdge> out = regionBoundary(segs, [](int w) { return w >= 1; });
    addVerticalConnectors(&out);
    return out;
}

}  // namespace ss::planar
