// How the strip walk bridges holes into the outer chain and cuts ears, strip triangles first.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/strip_walk.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <tuple>

namespace ss::planar {

namespace {

bool lessPoint(const IPoint& a, const IPoint& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; }

int64_t cross(const IPoint& a, const IPoint& b, const IPoint& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
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
    int link(std::span<const WalkPoint> chain) {
        int first = int(n_.size());
        for (size_t i = 0; i < chain.size(); ++i) {
            Node nd;
            nd.p = chain[i].p;
            nd.rings = chain[i].rings;
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

}  // namespace

bool walkPolygon(std::span<const WalkPoint> outer, std::span<const std::vector<WalkPoint>> holes,
                 std::vector<WalkTriangle>* out) {
    std::vector<Node> nodes;
    EarWalk walk(&nodes);
    int start = walk.link(outer);
    // Holes bridged left to right, each from its leftmost point.
    std::vector<std::pair<IPoint, int>> starts;
    for (const std::vector<WalkPoint>& hole : holes) {
        int first = walk.link(hole);
        int left = first;
        for (int i = first; i < first + int(hole.size()); ++i)
            if (lessPoint(nodes[size_t(i)].p, nodes[size_t(left)].p)) left = i;
        starts.push_back({nodes[size_t(left)].p, left});
    }
    std::sort(starts.begin(), starts.end(), [](auto& a, auto& b) { return lessPoint(a.first, b.first); });
    for (auto& [p, left] : starts)
        if (!walk.bridge(start, left)) return false;
    std::vector<std::array<int, 3>> tris;
    if (!walk.walk(start, &tris)) return false;
    for (const auto& t : tris) {
        WalkTriangle w;
        for (int i = 0; i < 3; ++i) w[size_t(i)] = WalkPoint{walk.node(t[size_t(i)]).p, walk.node(t[size_t(i)]).rings};
        out->push_back(w);
    }
    return true;
}

}  // namespace ss::planar
