// How the ring fill finds every strip's boundary in one sweep, labels its points with their
// rings and turns the walked triangles into the shadow mesh.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/ring_fill.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>

#include "planar/outline.h"
#include "planar/strip_walk.h"

namespace ss::planar {

namespace {

constexpr uint8_t kLower = 1;  // ring k, the strip's outer side
constexpr uint8_t kUpper = 2;  // ring k+1

bool lessPoint(const IPoint& a, const IPoint& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; }
using RingMask = std::map<IPoint, uint8_t, decltype(&lessPoint)>;

int64_t cross(const IPoint& a, const IPoint& b, const IPoint& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// The merged field's winding at points off the grid lines (px not an integer): the segments
// bucketed by the x columns they span, so a query reads one bucket.
class WindingProbe {
public:
    explicit WindingProbe(std::span<const SweepSegment> segs) : segs_(segs) {
        if (segs.empty()) return;
        x0_ = segs[0].seg.lo.x;
        int64_t x1 = segs[0].seg.hi.x;
        for (const SweepSegment& s : segs) {
            x0_ = std::min(x0_, s.seg.lo.x);
            x1 = std::max(x1, s.seg.hi.x);
        }
        buckets_.resize(std::clamp<size_t>(segs.size() / 4, 1, 4096));
        width_ = double(x1 - x0_ + 1) / double(buckets_.size());
        for (size_t i = 0; i < segs.size(); ++i)
            for (size_t b = bucket(double(segs[i].seg.lo.x)); b <= bucket(double(segs[i].seg.hi.x)); ++b)
                buckets_[b].push_back(uint32_t(i));
    }
    int at(double px, double py) const {
        if (buckets_.empty()) return 0;
        int w = 0;
        for (uint32_t i : buckets_[bucket(px)]) {
            const ISeg& s = segs_[i].seg;
            if (!(double(s.lo.x) < px && px < double(s.hi.x))) continue;
            double y = double(s.lo.y) + (px - double(s.lo.x)) * double(s.dy()) / double(s.dx());
            if (y < py) w += segs_[i].delta;
        }
        return w;
    }

private:
    size_t bucket(double x) const {
        return size_t(std::clamp((x - double(x0_)) / width_, 0.0, double(buckets_.size() - 1)));
    }
    std::span<const SweepSegment> segs_;
    int64_t x0_ = 0;
    double width_ = 1;
    std::vector<std::vector<uint32_t>> buckets_;
};

bool onInterior(const DirectedEdge& e, const IPoint& p) {
    if (p == e.a || p == e.b || cross(e.a, e.b, p) != 0) return false;
    return std::min(e.a.x, e.b.x) <= p.x && p.x <= std::max(e.a.x, e.b.x) && std::min(e.a.y, e.b.y) <= p.y &&
           p.y <= std::max(e.a.y, e.b.y);
}

// The strip {count == k}'s boundary edges, each with the ring it lies on.
struct LabelledBoundary {
    std::vector<DirectedEdge> edges;  // no vertical pieces (no slab sees them)
    std::vector<DirectedEdge> all;    // with the vertical pieces (addVerticalConnectors)
    std::vector<uint8_t> ring;        // per edge of `all`
};

IPoint roundPoint(const ISeg& s, const RatX& x) {
    RatY y = yAt(s, x);
    return IPoint{roundDiv(x.p, x.q), roundDiv(y.num, y.den)};
}

// Every strip's boundary (index k = 1..n-1, and n for the umbra, count >= n) from one sweep of
// the merged outlines: a segment group between counts w and w' bounds the strip of w on one
// side and the strip of w' on the other, each piece cut where its strip or its outside changes.
// Crossing points are rounded as in regionBoundary, so neighbouring strips share their chains.
std::vector<LabelledBoundary> stripBoundaries(std::span<const SweepSegment> segs, int n) {
    std::vector<LabelledBoundary> out(size_t(n) + 1);
    auto stripOf = [n](int w) { return w >= n ? n : std::max(w, 0); };
    struct Pending {
        bool open = false;
        int strip = 0, outside = 0;
        RatX x0, x1;
    };
    // Per segment: [0] the strip below it, [1] the strip above it.
    std::vector<std::array<Pending, 2>> pending(segs.size());
    auto flush = [&](int seg, int side) {
        Pending& p = pending[size_t(seg)][size_t(side)];
        if (!p.open) return;
        p.open = false;
        IPoint a = roundPoint(segs[size_t(seg)].seg, p.x0), b = roundPoint(segs[size_t(seg)].seg, p.x1);
        if (a == b) return;
        // A strip below a left-to-right piece lies on its right.
        LabelledBoundary& lb = out[size_t(p.strip)];
        lb.edges.push_back(side == 0 ? DirectedEdge{a, b, 1} : DirectedEdge{b, a, 1});
        lb.ring.push_back(p.outside < p.strip ? kLower : kUpper);
    };
    sweep(segs, [&](const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups) {
        int w = 0;
        for (const SlabGroup& g : groups) {
            const int below = w, above = w + g.delta;
            w = above;
            const int sb = stripOf(below), sa = stripOf(above);
            for (int side = 0; side < 2; ++side) {
                const int strip = side == 0 ? sb : sa, outside = side == 0 ? above : below;
                Pending& p = pending[size_t(g.seg)][size_t(side)];
                if (strip == 0 || sb == sa) {
                    flush(g.seg, side);
                    continue;
                }
                if (p.open && p.strip == strip && p.outside == outside && compareX(p.x1, xl) == 0) {
                    p.x1 = xr;
                    continue;
                }
                flush(g.seg, side);
                p = Pending{true, strip, outside, xl, xr};
            }
        }
    });
    for (size_t i = 0; i < segs.size(); ++i)
        for (int side = 0; side < 2; ++side) flush(int(i), side);
    WindingProbe probe(segs);
    for (int k = 1; k <= n; ++k) {
        LabelledBoundary& b = out[size_t(k)];
        b.all = b.edges;
        addVerticalConnectors(&b.all);
        // A vertical piece is in no slab: read the winding just outside it (the region is on
        // the right, so outside is east of a piece going down, west of one going up).
        for (size_t i = b.edges.size(); i < b.all.size(); ++i) {
            const DirectedEdge& e = b.all[i];
            bool down = (e.b.y < e.a.y) == (e.weight > 0);
            int wo = probe.at(double(e.a.x) + (down ? 0.5 : -0.5), 0.5 * double(e.a.y + e.b.y));
            b.ring.push_back(wo < k ? kLower : wo > k ? kUpper : uint8_t(kLower | kUpper));
        }
    }
    return out;
}

bool pointInChain(const Chain& chain, const IPoint& p) {
    bool in = false;
    for (size_t i = 0, j = chain.size() - 1; i < chain.size(); j = i++) {
        const IPoint &a = chain[i], &b = chain[j];
        if ((a.y > p.y) != (b.y > p.y)) {
            // p.x < x of the edge at p.y, exactly: sign of the cross product against the edge.
            i128 lhs = i128(p.x - a.x) * (b.y - a.y), rhs = i128(b.x - a.x) * (p.y - a.y);
            if ((b.y > a.y) ? lhs < rhs : lhs > rhs) in = !in;
        }
    }
    return in;
}

void emitFlatTrapezoids(std::span<const SweepSegment> segs, const RegionFn& inside, int n, ShadowMesh* mesh,
                        const std::function<float(const Trapezoid&, int corner)>& value) {
    for (const Trapezoid& t : trapezoids(segs, inside)) {
        bool umbra = t.winding >= n;
        mesh->shadowArea += t.area();
        if (umbra) mesh->umbraArea += t.area();
        int tris[2][3];
        int nt = triangulateCorners(t, tris);
        for (int i = 0; i < nt; ++i) {
            for (int k : tris[i]) {
                mesh->indices.push_back(uint32_t(mesh->vertices.size()));
                mesh->vertices.push_back(ShadowVertex{cornerX(t, k), cornerY(t, k), value(t, k)});
            }
            (umbra ? mesh->umbraTriangles : mesh->penumbraTriangles)++;
        }
    }
}

// Strip k (or with `umbra` the umbra, count >= k = n, flat 1) walked into triangles appended to
// `mesh`; false (mesh untouched) when a piece could not be walked. The umbra is walked on the
// same rounded chains as the strips around it, so the two meet without slivers.
bool walkStrip(const LabelledBoundary& lb, int k, int n, bool umbra, ShadowMesh* mesh, RingFillStats* stats) {
    if (lb.edges.empty()) return true;
    RingMask mask(&lessPoint);
    for (size_t i = 0; i < lb.all.size(); ++i) {
        mask[lb.all[i].a] |= lb.ring[i];
        mask[lb.all[i].b] |= lb.ring[i];
    }
    // A point of one ring touching the other inside one of its edges is on both. The mask is
    // ordered by x: each edge looks only at the points of its x range.
    for (size_t i = 0; i < lb.all.size(); ++i) {
        const DirectedEdge& e = lb.all[i];
        auto it = mask.lower_bound(IPoint{std::min(e.a.x, e.b.x), INT64_MIN});
        auto end = mask.upper_bound(IPoint{std::max(e.a.x, e.b.x), INT64_MAX});
        for (; it != end; ++it)
            if ((it->second | lb.ring[i]) != it->second && onInterior(e, it->first)) it->second |= lb.ring[i];
    }

    // The strip's boundary as closed chains, every point kept, turned to have the region on
    // the left: outer chains counter-clockwise, holes clockwise.
    std::vector<Chain> chains = linkChains(lb.edges, true);
    std::vector<Chain> outers, holes;
    for (Chain& c : chains) {
        std::reverse(c.begin(), c.end());
        (twiceSignedArea(c) > 0 ? outers : holes).push_back(std::move(c));
    }
    std::vector<std::vector<size_t>> holesOf(outers.size());
    for (size_t h = 0; h < holes.size(); ++h) {
        size_t best = outers.size();
        double bestArea = INFINITY;
        for (size_t o = 0; o < outers.size(); ++o) {
            // A hole point not on the outer chain decides; touching points say nothing.
            bool inside = false;
            for (const IPoint& p : holes[h]) {
                if (std::find(outers[o].begin(), outers[o].end(), p) != outers[o].end()) continue;
                inside = pointInChain(outers[o], p);
                break;
            }
            double area = double(twiceSignedArea(outers[o]));
            if (inside && area < bestArea) {
                best = o;
                bestArea = area;
            }
        }
        if (best == outers.size()) return false;
        holesOf[best].push_back(h);
    }

    const float lo = umbra ? 1.0f : ringIntensity(k, n), hi = umbra ? 1.0f : std::min(1.0f, ringIntensity(k + 1, n));
    ShadowMesh out;
    RingFillStats s;
    for (size_t o = 0; o < outers.size(); ++o) {
        auto tagged = [&](const Chain& c) {
            std::vector<WalkPoint> out;
            for (const IPoint& p : c) {
                auto it = mask.find(p);
                out.push_back(WalkPoint{p, it == mask.end() ? uint8_t(0) : it->second});
            }
            return out;
        };
        std::vector<std::vector<WalkPoint>> holePoints;
        for (size_t h : holesOf[o]) holePoints.push_back(tagged(holes[h]));
        std::vector<WalkTriangle> tris;
        if (!walkPolygon(tagged(outers[o]), holePoints, &tris)) return false;
        i128 twice = twiceSignedArea(outers[o]), covered = 0;
        for (size_t h : holesOf[o]) twice += twiceSignedArea(holes[h]);
        for (const WalkTriangle& t : tris) covered += cross(t[0].p, t[1].p, t[2].p);
        // Exact when the chains are simple. Rounded crossing points (< 0.71 grid units) can make
        // two nearly parallel chain edges cross; the walk then covers that sliver (at most a
        // unit wide along the boundary) twice or not at all, far below a pixel. Anything more
        // is not a tiling: the strip falls back.
        double perimeter = 0;
        auto addPerimeter = [&](const Chain& c) {
            for (size_t i = 0; i < c.size(); ++i) {
                const IPoint &a = c[i], &b = c[(i + 1) % c.size()];
                // sqrt, not std::hypot: glibc 2.35 re-versioned hypot, and the zip must load on
                // older systems (tests/blender/test_package.py); grid coordinates cannot overflow.
                const double dx = double(b.x - a.x), dy = double(b.y - a.y);
                perimeter += std::sqrt(dx * dx + dy * dy);
            }
        };
        addPerimeter(outers[o]);
        for (size_t h : holesOf[o]) addPerimeter(holes[h]);
        i128 off = covered - twice;
        if (covered != twice) ++s.roundedStrips;
        if (double(off < 0 ? -off : off) > 2.0 * perimeter) return false;  // a strip not tiled exactly is not shown
        for (const WalkTriangle& t : tris) {
            uint8_t r0 = t[0].rings, r1 = t[1].rings, r2 = t[2].rings;
            // A bay: every corner on the same one ring, so flat. A leak triangle: corners on one
            // ring and crossing points, interpolating from the crossing's mean to that ring.
            bool bay = r0 == r1 && r1 == r2 && (r0 == kLower || r0 == kUpper);
            bool strip = ((r0 | r1 | r2) & kLower) && ((r0 | r1 | r2) & kUpper) && !((r0 & r1 & r2) & kLower) &&
                         !((r0 & r1 & r2) & kUpper);
            if (!umbra) (bay ? s.bayTriangles : strip ? s.stripTriangles : s.leakTriangles)++;
            for (const WalkPoint& v : t) {
                float value = v.rings == kUpper ? hi : v.rings == (kLower | kUpper) ? 0.5f * (lo + hi) : lo;
                out.indices.push_back(uint32_t(out.vertices.size()));
                out.vertices.push_back(ShadowVertex{double(v.p.x), double(v.p.y), value});
            }
            (umbra ? out.umbraTriangles : out.penumbraTriangles)++;
        }
        out.shadowArea += double(twice) / 2.0;
        if (umbra) out.umbraArea += double(twice) / 2.0;
    }
    if (!umbra)
        for (const auto& [p, bits] : mask) s.crossingVertices += bits == (kLower | kUpper);
    const uint32_t base = uint32_t(mesh->vertices.size());
    mesh->vertices.insert(mesh->vertices.end(), out.vertices.begin(), out.vertices.end());
    for (uint32_t i : out.indices) mesh->indices.push_back(base + i);
    mesh->penumbraTriangles += out.penumbraTriangles;
    mesh->umbraTriangles += out.umbraTriangles;
    mesh->shadowArea += out.shadowArea;
    mesh->umbraArea += out.umbraArea;
    if (stats) {
        stats->stripTriangles += s.stripTriangles;
        stats->bayTriangles += s.bayTriangles;
        stats->leakTriangles += s.leakTriangles;
        stats->crossingVertices += s.crossingVertices;
        stats->roundedStrips += s.roundedStrips;
    }
    return true;
}

}  // namespace

ShadowMesh fillRings(std::span<const DirectedEdge> mergedEdges, int samples, RingFillStats* stats) {
    ShadowMesh mesh;
    std::vector<SweepSegment> segs = toSweepSegments(mergedEdges);
    const int n = std::max(samples, 1);
    std::vector<LabelledBoundary> boundaries = stripBoundaries(segs, n);
    for (int k = 1; k <= n; ++k) {
        const bool umbra = k == n;
        if (walkStrip(boundaries[size_t(k)], k, n, umbra, &mesh, stats)) continue;
        // Fallback: the region's trapezoids, each side at the intensity of the ring it lies on.
        if (stats) stats->fallbackStrips++;
        mesh.ringFallbacks++;
        const float lo = umbra ? 1.0f : ringIntensity(k, n), hi = umbra ? 1.0f : std::min(1.0f, ringIntensity(k + 1, n));
        emitFlatTrapezoids(segs, [k, umbra](int w) { return umbra ? w >= k : w == k; }, n, &mesh,
                           [&](const Trapezoid& t, int corner) {
                               int across = corner < 2 ? t.windingBelow : t.windingAbove;
                               return across < k ? lo : hi;
                           });
    }
    return mesh;
}

}  // namespace ss::planar
