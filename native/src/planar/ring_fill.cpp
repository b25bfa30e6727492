// How the ring fill labels each strip's boundary points with their rings, bridges holes and
// walks the strip into triangles.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/ring_fill.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <queue>
#include <tuple>

#include "planar/outline.h"

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

struct Node {
    IPoint p;
    uint8_t rings = 0;
    int prev = -1, next = -1;
    int version = 0;  // bumped when a neighbour changes, so queued candidates go stale
    bool removed = false;
};

// One piece of a strip: an outer chain with its holes bridged in, walked into triangles.
class EarWalk {
public:
    explicit EarWalk(std::vector<Node>* nodes) : n_(*nodes) {}

    // Links `chain` (counter-clockwise for an outer boundary, clockwise for a hole) as a cycle;
    // returns one of its nodes.
    int link(const std::vector<IPoint>& chain, const RingMask& mask) {
        int first = int(n_.size());
        for (size_t i = 0; i < chain.size(); ++i) {
            Node nd;
            nd.p = chain[i];
            auto it = mask.find(chain[i]);
            nd.rings = it == mask.end() ? 0 : it->second;
            nd.prev = first + int((i + chain.size() - 1) % chain.size());
            nd.next = first + int((i + 1) % chain.size());
            n_.push_back(nd);
        }
        return first;
    }

    // Joins a hole (starting at its leftmost node) to the polygon through `outer`.
    bool bridge(int outer, int hole) {
        int m = findBridge(outer, hole);
        if (m < 0) return false;
        int a2 = int(n_.size()), b2 = a2 + 1;
        const Node nm = n_[m], nh = n_[hole];
        n_.push_back(nm);
        n_.push_back(nh);
        int an = n_[m].next, bp = n_[hole].prev;
        n_[m].next = hole;
        n_[hole].prev = m;
        n_[a2].next = an;
        n_[an].prev = a2;
        n_[b2].next = a2;
        n_[a2].prev = b2;
        n_[bp].next = b2;
        n_[b2].prev = bp;
        return true;
    }

    // Cuts the polygon through `start` into triangles; false when it gets stuck.
    bool walk(int start, std::vector<std::array<int, 3>>* tris) {
        using Key = std::tuple<int, double, int, int>;  // (bay?, diagonal², node, version)
        std::priority_queue<Key, std::vector<Key>, std::greater<Key>> queue;
        auto push = [&](int b) {
            const Node& nb = n_[b];
            const Node &na = n_[nb.prev], &nc = n_[nb.next];
            double dx = double(nc.p.x - na.p.x), dy = double(nc.p.y - na.p.y);
            int bay = (na.rings & nb.rings & nc.rings) != 0 ? 1 : 0;
            // A spike (a, b, c on a line, b not between a and c) encloses nothing: dropped first.
            if (cross(na.p, nb.p, nc.p) == 0 &&
                (nb.p.x - na.p.x) * (nc.p.x - nb.p.x) + (nb.p.y - na.p.y) * (nc.p.y - nb.p.y) <= 0)
                bay = -1;
            queue.push(Key{bay, dx * dx + dy * dy, b, nb.version});
        };
        int left = 0;
        for (int i = start;;) {
            ++left;
            i = n_[i].next;
            if (i == start) break;
        }
        while (left > 3) {
            // Candidates refused earlier may have been blocked by points since cut away.
            int alive = start;
            while (n_[alive].removed) alive = n_[alive].next;
            for (int i = alive;;) {
                push(i);
                i = n_[i].next;
                if (i == alive) break;
            }
            bool progress = false;
            while (!queue.empty() && left > 3) {
                auto [bay, d2, b, version] = queue.top();
                queue.pop();
                if (n_[b].removed || n_[b].version != version) continue;
                int a = n_[b].prev, c = n_[b].next;
                if (bay >= 0 && !isEar(a, b, c)) continue;
                if (bay >= 0) tris->push_back({a, b, c});
                n_[b].removed = true;
                n_[a].next = c;
                n_[c].prev = a;
                ++n_[a].version;
                ++n_[c].version;
                start = a;
                --left;
                progress = true;
                push(a);
                push(c);
            }
            if (left <= 3) break;
            if (!progress) return false;
        }
        int a = start, b = n_[a].next, c = n_[b].next;
        if (left == 3 && cross(n_[a].p, n_[b].p, n_[c].p) > 0) tris->push_back({a, b, c});
        return true;
    }

    const Node& node(int i) const { return n_[i]; }

private:
    // Inside the wedge at node p (interior on the left of prev -> p -> next)?
    bool inWedge(int p, double x, double y) const {
        const IPoint &a = n_[n_[p].prev].p, &b = n_[p].p, &c = n_[n_[p].next].p;
        auto side = [](const IPoint& u, const IPoint& v, double x, double y) {
            return double(v.x - u.x) * (y - double(u.y)) - double(v.y - u.y) * (x - double(u.x));
        };
        bool l1 = side(a, b, x, y) > 0, l2 = side(b, c, x, y) > 0;
        return cross(a, b, c) > 0 ? (l1 && l2) : (l1 || l2);
    }

    // No other point of the polygon in the triangle or on its sides, and no other wedge at one
    // of its corners reaching into it: then cutting it leaves the rest a polygon and overlaps
    // nothing.
    bool isEar(int a, int b, int c) const {
        const IPoint &pa = n_[a].p, &pb = n_[b].p, &pc = n_[c].p;
        if (cross(pa, pb, pc) <= 0) return false;
        double cx = double(pa.x + pb.x + pc.x) / 3.0, cy = double(pa.y + pb.y + pc.y) / 3.0;
        for (int p = n_[c].next; p != a; p = n_[p].next) {
            const IPoint& q = n_[p].p;
            if (q == pa || q == pb || q == pc) {
                if (inWedge(p, cx, cy)) return false;
                continue;
            }
            if (cross(pa, pb, q) >= 0 && cross(pb, pc, q) >= 0 && cross(pc, pa, q) >= 0) return false;
        }
        return true;
    }

    // The outer node the hole's leftmost node can see: the nearest polygon edge to its left
    // along its row, then the point of smallest angle inside the triangle that leaves.
    int findBridge(int outer, int hole) const {
        const IPoint h = n_[hole].p;
        double qx = -INFINITY;
        int m = -1;
        int p = outer;
        do {
            const IPoint &u = n_[p].p, &v = n_[n_[p].next].p;
            if (h.y <= u.y && h.y >= v.y && v.y != u.y) {
                double x = double(u.x) + double(h.y - u.y) * double(v.x - u.x) / double(v.y - u.y);
                if (x <= double(h.x) && x > qx) {
                    qx = x;
                    m = u.x < v.x ? p : n_[p].next;
                    if (x == double(h.x)) return m;
                }
            }
            p = n_[p].next;
        } while (p != outer);
        if (m < 0) return -1;
        const int stop = m;
        const IPoint mp = n_[m].p;
        double tanMin = INFINITY;
        p = m;
        do {
            const IPoint& q = n_[p].p;
            if (h.x >= q.x && q.x >= mp.x && h.x != q.x && inTriangle(h.y < mp.y ? double(h.x) : qx, double(h.y), mp,
                                                                      h.y < mp.y ? qx : double(h.x), q)) {
                double tan = std::abs(double(h.y - q.y)) / double(h.x - q.x);
                if (inWedge(p, double(h.x), double(h.y)) && (tan < tanMin || (tan == tanMin && q.x > n_[m].p.x))) {
                    m = p;
                    tanMin = tan;
                }
            }
            p = n_[p].next;
        } while (p != stop);
        return m;
    }

    static bool inTriangle(double ax, double ay, const IPoint& b, double cx, const IPoint& q) {
        double cy = ay;
        double px = double(q.x), py = double(q.y);
        return (cx - px) * (ay - py) >= (ax - px) * (cy - py) &&
               (ax - px) * (double(b.y) - py) >= (double(b.x) - px) * (ay - py) &&
               (double(b.x) - px) * (cy - py) >= (cx - px) * (double(b.y) - py);
    }

    std::vector<Node>& n_;
};

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
        std::vector<Node> nodes;
        EarWalk walk(&nodes);
        int start = walk.link(outers[o], mask);
        // Holes bridged left to right, each from its leftmost point.
        std::vector<std::pair<IPoint, int>> starts;
        for (size_t h : holesOf[o]) {
            int first = walk.link(holes[h], mask);
            int left = first;
            for (int i = first; i < first + int(holes[h].size()); ++i)
                if (lessPoint(nodes[i].p, nodes[left].p)) left = i;
            starts.push_back({nodes[left].p, left});
        }
        std::sort(starts.begin(), starts.end(), [](auto& a, auto& b) { return lessPoint(a.first, b.first); });
        for (auto& [p, left] : starts)
            if (!walk.bridge(start, left)) return false;
        std::vector<std::array<int, 3>> tris;
        if (!walk.walk(start, &tris)) return false;
        i128 twice = twiceSignedArea(outers[o]), covered = 0;
        for (size_t h : holesOf[o]) twice += twiceSignedArea(holes[h]);
        for (const auto& t : tris) covered += cross(walk.node(t[0]).p, walk.node(t[1]).p, walk.node(t[2]).p);
        // Exact when the chains are simple. Rounded crossing points (< 0.71 grid units) can make
        // two nearly parallel chain edges cross; the walk then covers that sliver (at most a
        // unit wide along the boundary) twice or not at all, far below a pixel. Anything more
        // is not a tiling: the strip falls back.
        double perimeter = 0;
        auto addPerimeter = [&](const Chain& c) {
            for (size_t i = 0; i < c.size(); ++i) {
                const IPoint &a = c[i], &b = c[(i + 1) % c.size()];
                perimeter += std::hypot(double(b.x - a.x), double(b.y - a.y));
            }
        };
        addPerimeter(outers[o]);
        for (size_t h : holesOf[o]) addPerimeter(holes[h]);
        i128 off = covered - twice;
        if (covered != twice) ++s.roundedStrips;
        if (double(off < 0 ? -off : off) > 2.0 * perimeter) return false;  // a strip not tiled exactly is not shown
        for (const auto& t : tris) {
            uint8_t r0 = walk.node(t[0]).rings, r1 = walk.node(t[1]).rings, r2 = walk.node(t[2]).rings;
            // A bay: every corner on the same one ring, so flat. A leak triangle: corners on one
            // ring and crossing points, interpolating from the crossing's mean to that ring.
            bool bay = r0 == r1 && r1 == r2 && (r0 == kLower || r0 == kUpper);
            bool strip = ((r0 | r1 | r2) & kLower) && ((r0 | r1 | r2) & kUpper) && !((r0 & r1 & r2) & kLower) &&
                         !((r0 & r1 & r2) & kUpper);
            if (!umbra) (bay ? s.bayTriangles : strip ? s.stripTriangles : s.leakTriangles)++;
            for (int i : t) {
                const Node& v = walk.node(i);
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
