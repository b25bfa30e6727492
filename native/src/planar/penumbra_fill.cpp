// How trapezoids of the merged sweep get their corner intensities from the rings and become
// triangles: ring edges carry their ring's intensity, a point where rings meet the mean of
// the rings there, edges where several rings coincide interpolate between their end points.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/penumbra_fill.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <numeric>
#include <span>
#include <tuple>

#include "planar/ring_fill.h"

namespace ss::planar {

namespace {

// A maximal run of one segment group along which the counts on both sides stay the same.
struct Incident;
struct Run {
    RatX x0, x1;
    int lo = 0, hi = 0;  // counts on its two sides, lo < hi, clamped to [0, n]
    // The edges meeting at each end: ranges of the vertex table (filled once it is complete).
    uint32_t at0 = 0, count0 = 0, at1 = 0, count1 = 0;
};

i128 gcd128(i128 a, i128 b) {
    if (a < 0) a = -a;
    if (b < 0) b = -b;
    // Most values fit in 64 bits (grid x, y over a segment's dx): the hardware divide is far
    // cheaper than the 128-bit one.
    constexpr i128 kMax = i128(INT64_MAX);
    if (a <= kMax && b <= kMax) return std::gcd(int64_t(a), int64_t(b));
    while (b != 0) {
        i128 t = a % b;
        a = b;
        b = t;
    }
    return a;
}

// An exact point in lowest terms, so the same point reached from two segments is one key.
struct PointKey {
    i128 xp, xq, yn, yd;
    bool operator==(const PointKey&) const = default;
    bool operator<(const PointKey& o) const { return std::tie(xp, xq, yn, yd) < std::tie(o.xp, o.xq, o.yn, o.yd); }
};

PointKey keyOf(const ISeg& s, const RatX& x) {
    RatY y = yAt(s, x);
    i128 gx = gcd128(x.p, x.q), gy = gcd128(y.num, y.den);
    if (gx == 0) gx = 1;
    if (gy == 0) gy = 1;
    return PointKey{x.p / gx, i128(x.q) / gx, y.num / gy, y.den / gy};
}

// One ring-carrying edge at a vertex: the counts on its sides and which way it leaves.
enum class Leaves { Left, Right, Up, Down };
struct Incident {
    int lo = 0, hi = 0;  // carries rings lo+1 .. hi
    Leaves dir = Leaves::Left;
    int seg = -1;        // its segment (non-vertical edges), for the collinearity test
};

// A vertical edge is in no slab; its counts left and right are read from the slabs beside it.
struct Vertical {
    int64_t x, y0, y1;  // y0 < y1
    int left = 0, right = 0;
};

// sign(y_s(x) - y) with y given as twice its value (y may be a half-integer).
int compareWithHalf(const ISeg& s, const RatX& x, int64_t twiceY) {
    RatY v = yAt(s, x);
    return sign(2 * v.num - i128(twiceY) * v.den);
}

int windingAt(std::span<const SweepSegment> segs, std::span<const SlabGroup> groups, const RatX& x,
              int64_t twiceY) {
    int w = 0;
    for (const SlabGroup& g : groups) {
        if (compareWithHalf(segs[g.seg].seg, x, twiceY) >= 0) break;
        w += g.delta;
    }
    return w;
}

class RingField {
public:
    // `also` receives every slab of the same sweep (the trapezoids), so the merged outlines
    // are swept once.
    RingField(std::span<const SweepSegment> segs, std::span<const DirectedEdge> edges, int n,
              TrapezoidCollector* also)
        : segs_(segs), n_(n), runs_(segs.size()) {
        std::vector<Vertical> verticals;
        for (const DirectedEdge& e : edges)
            if (e.a.x == e.b.x && e.a.y != e.b.y)
                verticals.push_back(Vertical{e.a.x, std::min(e.a.y, e.b.y), std::max(e.a.y, e.b.y)});
        std::sort(verticals.begin(), verticals.end(), [](const Vertical& a, const Vertical& b) { return a.x < b.x; });
        auto verticalsAt = [&](const RatX& x) {
            // Only grid x can hold a vertical edge.
            if (x.p % x.q != 0) return std::pair<size_t, size_t>{0, 0};
            int64_t X = int64_t(x.p / x.q);
            auto lo = std::lower_bound(verticals.begin(), verticals.end(), X,
                                       [](const Vertical& v, int64_t X) { return v.x < X; });
            auto hi = std::upper_bound(verticals.begin(), verticals.end(), X,
                                       [](int64_t X, const Vertical& v) { return X < v.x; });
            return std::pair<size_t, size_t>{size_t(lo - verticals.begin()), size_t(hi - verticals.begin())};
        };
        // The slab that last extended each segment's runs (0: none yet); a run goes on only
        // into the next slab, and only when that slab starts where the last one ended.
        std::vector<size_t> lastSlab(segs.size(), 0);
        size_t slab = 0;
        RatX lastXr;
        sweep(segs, [&](const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups) {
            if (also) also->onSlab(xl, xr, groups);
            ++slab;
            const bool touchesLast = slab > 1 && compareX(lastXr, xl) == 0;
            lastXr = xr;
            auto [r0, r1] = verticalsAt(xl);
            for (size_t i = r0; i < r1; ++i)
                verticals[i].right = windingAt(segs, groups, xl, verticals[i].y0 + verticals[i].y1);
            auto [l0, l1] = verticalsAt(xr);
            for (size_t i = l0; i < l1; ++i)
                verticals[i].left = windingAt(segs, groups, xr, verticals[i].y0 + verticals[i].y1);
            int w = 0;
            for (const SlabGroup& g : groups) {
                int below = std::clamp(w, 0, n_), above = std::clamp(w + g.delta, 0, n_);
                w += g.delta;
                if (below == above) continue;
                Run r{xl, xr, std::min(below, above), std::max(below, above)};
                auto& list = runs_[g.seg];
                if (touchesLast && lastSlab[g.seg] == slab - 1 && list.back().lo == r.lo && list.back().hi == r.hi) {
                    list.back().x1 = xr;
                } else {
                    list.push_back(r);
                }
                lastSlab[g.seg] = slab;
            }
        });
        buildVertexTable(verticals);
    }

    // The intensity at x on segment group `seg`, seen from a region of count c whose side there
    // lies on ring `ring` (c or c+1).
    float at(int seg, const RatX& x, int c, int ring) const {
        const auto& list = runs_[seg];
        auto it = std::lower_bound(list.begin(), list.end(), x,
                                   [](const Run& r, const RatX& v) { return compareX(r.x1, v) < 0; });
        float own = ringIntensity(ring, n_);
        if (it == list.end()) return own;  // not on a ring: cannot happen for a trapezoid side
        const Run& r = *it;
        if (compareX(x, r.x0) == 0) return vertex(startOf(r), c, own);
        if (compareX(x, r.x1) == 0) return vertex(endOf(r), c, own);
        if (r.hi - r.lo == 1) return own;
        // Coincident rings: interpolate between the points where they part.
        double t = (x.toDouble() - r.x0.toDouble()) / (r.x1.toDouble() - r.x0.toDouble());
        float v0 = vertex(startOf(r), c, own), v1 = vertex(endOf(r), c, own);
        return float(v0 + t * (v1 - v0));
    }

private:
    // Every end of a run and of a vertical ring edge, sorted by point: the edges meeting at a
    // point are one range of `incident_`, which each run keeps for its two ends.
    void buildVertexTable(std::span<const Vertical> verticals) {
        struct End {
            PointKey at;
            Incident incident;
            Run* run;  // null for a vertical edge
        };
        std::vector<End> ends;
        for (size_t s = 0; s < runs_.size(); ++s)
            for (Run& r : runs_[s]) {
                ends.push_back(End{keyOf(segs_[s].seg, r.x0), Incident{r.lo, r.hi, Leaves::Right, int(s)}, &r});
                ends.push_back(End{keyOf(segs_[s].seg, r.x1), Incident{r.lo, r.hi, Leaves::Left, int(s)}, &r});
            }
        for (const Vertical& e : verticals) {
            int lo = std::clamp(std::min(e.left, e.right), 0, n_), hi = std::clamp(std::max(e.left, e.right), 0, n_);
            if (lo == hi) continue;
            ends.push_back(End{PointKey{e.x, 1, e.y0, 1}, Incident{lo, hi, Leaves::Up, -1}, nullptr});
            ends.push_back(End{PointKey{e.x, 1, e.y1, 1}, Incident{lo, hi, Leaves::Down, -1}, nullptr});
        }
        std::sort(ends.begin(), ends.end(), [](const End& a, const End& b) { return a.at < b.at; });
        incident_.reserve(ends.size());
        for (const End& e : ends) incident_.push_back(e.incident);
        for (size_t i = 0; i < ends.size();) {
            size_t j = i + 1;
            while (j < ends.size() && ends[j].at == ends[i].at) ++j;
            for (size_t k = i; k < j; ++k) {
                Run* r = ends[k].run;
                if (!r) continue;
                // A run leaving to the right starts here; one leaving to the left ends here.
                if (ends[k].incident.dir == Leaves::Right) {
                    r->at0 = uint32_t(i), r->count0 = uint32_t(j - i);
                } else {
                    r->at1 = uint32_t(i), r->count1 = uint32_t(j - i);
                }
            }
            i = j;
        }
    }

    std::span<const Incident> startOf(const Run& r) const { return {incident_.data() + r.at0, r.count0}; }
    std::span<const Incident> endOf(const Run& r) const { return {incident_.data() + r.at1, r.count1}; }

    // A ring of level L has a corner at a vertex unless exactly two of its edges meet there and
    // go straight on. The region's rings (c, c+1) with a corner here give the vertex its value,
    // their mean when both do (the paper's intersection point); otherwise the side's own ring.
    float vertex(std::span<const Incident> incident, int c, float own) const {
        double sum = 0;
        int count = 0;
        for (int level : {c, c + 1}) {
            if (level < 1 || level > n_) continue;
            const Incident* found[3];
            int k = 0;
            for (const Incident& e : incident)
                if (e.lo < level && level <= e.hi) {
                    if (k < 3) found[k] = &e;
                    ++k;
                }
            if (k == 0) continue;
            bool straight = false;
            if (k == 2) {
                const Incident& a = *found[0];
                const Incident& b = *found[1];
                auto opposite = [](Leaves p, Leaves q) {
                    return (p == Leaves::Left && q == Leaves::Right) || (p == Leaves::Right && q == Leaves::Left) ||
                           (p == Leaves::Up && q == Leaves::Down) || (p == Leaves::Down && q == Leaves::Up);
                };
                if (opposite(a.dir, b.dir))
                    straight = a.seg < 0 || a.seg == b.seg || compareSlope(segs_[a.seg].seg, segs_[b.seg].seg) == 0;
            }
            if (straight) continue;
            sum += ringIntensity(level, n_);
            ++count;
        }
        return count > 0 ? float(sum / count) : own;
    }

    std::span<const SweepSegment> segs_;
    int n_;
    std::vector<std::vector<Run>> runs_;
    std::vector<Incident> incident_;  // grouped by point (buildVertexTable)
};

}  // namespace
ShadowMesh fillShadow(std::span<const DirectedEdge> mergedEdges, int samples, FillMode mode) {
    if (mode == FillMode::Rings) return fillRings(mergedEdges, samples);
    ShadowMesh mesh;
    std::vector<SweepSegment> merged = toSweepSegments(mergedEdges);
    const int n = std::max(samples, 1);
    bool smooth = mode == FillMode::Smooth && n > 1;
    std::unique_ptr<RingField> field;
    std::vector<Trapezoid> traps;
    if (smooth) {
        TrapezoidCollector collector(merged, [](int w) { return w >= 1; });
        field = std::make_unique<RingField>(merged, mergedEdges, n, &collector);
        traps = collector.finish();
    } else {
        traps = trapezoids(merged, [](int w) { return w >= 1; });
    }
    for (const Trapezoid& t : traps) {
        int c = std::clamp(t.winding, 0, n);
        bool umbra = c >= n;
        double area = t.area();
        mesh.shadowArea += area;
        if (umbra) mesh.umbraArea += area;
        float corner[4];
        for (int k = 0; k < 4; ++k) {
            if (!smooth) {
                corner[k] = float(c) / float(n);
                continue;
            }
            // A count-c region lies between ring c and ring c+1.
            float lo = ringIntensity(c, n), hi = std::min(1.0f, ringIntensity(c + 1, n));
            bool bottom = k < 2;
            int seg = bottom ? t.bottomSeg : t.topSeg;
            int across = std::clamp(bottom ? t.windingBelow : t.windingAbove, 0, n);
            int ring = across < c ? c : c + 1;
            const RatX& x = (k == 0 || k == 3) ? t.rx0 : t.rx1;
            corner[k] = std::clamp(field->at(seg, x, c, ring), lo, hi);
        }
        int tris[2][3];
        int nt = triangulateCorners(t, tris);
        for (int i = 0; i < nt; ++i) {
            for (int k : tris[i]) {
                mesh.indices.push_back(uint32_t(mesh.vertices.size()));
                mesh.vertices.push_back(ShadowVertex{cornerX(t, k), cornerY(t, k), corner[k]});
            }
            (umbra ? mesh.umbraTriangles : mesh.penumbraTriangles)++;
        }
    }
    return mesh;
}

}  // namespace ss::planar
