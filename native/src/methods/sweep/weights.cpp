// How each shadow-mesh corner gets the irradiance-weighted share of the light its region's
// shadowing samples stand for.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/weights.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>
#include <utility>

namespace ss {

namespace {

// One sample's outline cut into horizontal bands, so a point's winding number reads only the
// edges spanning its band (about 2 per band) rather than the whole outline.
class BandedOutline {
public:
    explicit BandedOutline(std::span<const planar::DirectedEdge> edges) : edges_(edges.begin(), edges.end()) {
        if (edges_.empty()) return;
        y0_ = y1_ = double(edges_[0].a.y);
        x0_ = x1_ = double(edges_[0].a.x);
        for (const planar::DirectedEdge& e : edges_) {
            y0_ = std::min({y0_, double(e.a.y), double(e.b.y)});
            y1_ = std::max({y1_, double(e.a.y), double(e.b.y)});
            x0_ = std::min({x0_, double(e.a.x), double(e.b.x)});
            x1_ = std::max({x1_, double(e.a.x), double(e.b.x)});
        }
        bands_ = std::max<size_t>(1, edges_.size() / 2);
        height_ = std::max(1.0, (y1_ - y0_) / double(bands_));
        std::vector<uint32_t> count(bands_ + 1, 0);
        auto range = [&](const planar::DirectedEdge& e, size_t* lo, size_t* hi) {
            *lo = band(std::min(e.a.y, e.b.y));
            *hi = band(std::max(e.a.y, e.b.y));
        };
        for (const planar::DirectedEdge& e : edges_) {
            size_t lo, hi;
            range(e, &lo, &hi);
            for (size_t k = lo; k <= hi; ++k) ++count[k + 1];
        }
        for (size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
        start_ = count;
        items_.resize(count.back());
        for (const planar::DirectedEdge& e : edges_) {
            size_t lo, hi;
            range(e, &lo, &hi);
            const Item item{double(e.a.x), double(e.a.y), double(e.b.x), double(e.b.y), e.weight};
            for (size_t k = lo; k <= hi; ++k) items_[count[k]++] = item;
        }
    }

    // Winding number around (x, y), a point on none of the edges.
    int winding(double x, double y) const {
        if (edges_.empty() || y < y0_ || y > y1_ || x < x0_ || x > x1_) return 0;
        size_t k = band(y);
        int w = 0;
        for (uint32_t i = start_[k]; i < start_[k + 1]; ++i) {
            const Item& e = items_[i];
            if ((e.ay <= y) == (e.by <= y)) continue;
            double side = (e.bx - e.ax) * (y - e.ay) - (e.by - e.ay) * (x - e.ax);
            if (e.by > e.ay && side > 0) w += e.weight;
            else if (e.by <= e.ay && side < 0) w -= e.weight;
        }
        return w;
    }

private:
    size_t band(double y) const {
        return std::min(bands_ - 1, size_t(std::max(0.0, std::floor((y - y0_) / height_))));
    }
    std::vector<planar::DirectedEdge> edges_;
    double x0_ = 0, x1_ = 0, y0_ = 0, y1_ = 0, height_ = 1;
    size_t bands_ = 1;
    // Each band's edges stored in place (as doubles), so a query reads one contiguous run.
    struct Item {
        double ax, ay, bx, by;
        int weight;
    };
    std::vector<uint32_t> start_;
    std::vector<Item> items_;
};

}  // namespace

namespace {

// Which slot each distinct corner position has: open addressing with linear probing on a
// power-of-two table (a node-based map spends most of the weights stage allocating and chasing
// nodes). Positions compare as doubles do (0 and -0 are one position).
class CornerIndex {
public:
    explicit CornerIndex(size_t expected) {
        size_t capacity = 16;
        while (capacity < 2 * expected) capacity *= 2;
        slots_.resize(capacity);
    }
    // The slot of (x, y); a new position gets `next` and sets *added.
    uint32_t find(double x, double y, uint32_t next, bool* added) {
        if (2 * (used_ + 1) > slots_.size()) grow();
        const size_t mask = slots_.size() - 1;
        for (size_t i = hash(x, y) & mask;; i = (i + 1) & mask) {
            Slot& s = slots_[i];
            if (s.index == kEmpty) {
                s = Slot{x, y, next};
                ++used_;
                *added = true;
                return next;
            }
            if (s.x == x && s.y == y) {
                *added = false;
                return s.index;
            }
        }
    }

private:
    static constexpr uint32_t kEmpty = 0xFFFFFFFFu;
    struct Slot {
        double x = 0, y = 0;
        uint32_t index = kEmpty;
    };
    static uint64_t bits(double v) {
        if (v == 0.0) return 0;  // -0 equals 0
        uint64_t b;
        std::memcpy(&b, &v, sizeof b);
        return b;
    }
    static size_t hash(double x, double y) {
        uint64_t h = bits(x) * 0x9E3779B97F4A7C15ull ^ bits(y);
        h ^= h >> 32;
        h *= 0xD6E8FEB86659FD93ull;
        h ^= h >> 32;
        return size_t(h);
    }
    void grow() {
        std::vector<Slot> old = std::move(slots_);
        slots_.assign(old.size() * 2, Slot{});
        const size_t mask = slots_.size() - 1;
        for (const Slot& s : old) {
            if (s.index == kEmpty) continue;
            size_t i = hash(s.x, s.y) & mask;
            while (slots_[i].index != kEmpty) i = (i + 1) & mask;
            slots_[i] = s;
        }
    }
    std::vector<Slot> slots_;
    size_t used_ = 0;
};

// sampleIrradianceWeight with the emitter's direction computed once (null: no cosine there).
double weightTowards(const glm::dvec3* emits, const LightSample& s, const glm::dvec3& p, const glm::dvec3& n) {
    if (s.directional) return std::max(0.0, glm::dot(n, s.toLight));
    glm::dvec3 r = s.point - p;
    double d2 = glm::dot(r, r);
    if (!(d2 > 0)) return 0.0;
    double d = std::sqrt(d2);
    double cosR = glm::dot(n, r) / d;
    if (cosR <= 0) return 0.0;
    double cosL = 1.0;
    if (emits) {
        cosL = glm::dot(*emits, -r) / d;
        if (cosL <= 0) return 0.0;  // behind the one-sided emitter
    }
    return cosL * cosR / d2;
}

}  // namespace

double sampleIrradianceWeight(const Light& light, const LightSample& s, const glm::dvec3& p, const glm::dvec3& n) {
    const glm::dvec3 emits(light.direction());
    return weightTowards(light.isArea() ? &emits : nullptr, s, p, n);
}

namespace {

// Where two outlines of one sample differ, as multisets of edges: the bounding box of the edges
// either has and the other has not (`any` false when they are the same).
struct ChangedBox {
    bool any = false;
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    void extend(const planar::DirectedEdge& e) {
        const double ex0 = double(std::min(e.a.x, e.b.x)), ex1 = double(std::max(e.a.x, e.b.x));
        const double ey0 = double(std::min(e.a.y, e.b.y)), ey1 = double(std::max(e.a.y, e.b.y));
        if (!any) {
            x0 = ex0, x1 = ex1, y0 = ey0, y1 = ey1, any = true;
            return;
        }
        x0 = std::min(x0, ex0), x1 = std::max(x1, ex1), y0 = std::min(y0, ey0), y1 = std::max(y1, ey1);
    }
    // Strictly outside: on the box's border counts as inside.
    bool outside(double x, double y) const { return !any || x < x0 || x > x1 || y < y0 || y > y1; }
};

auto edgeTuple(const planar::DirectedEdge& e) { return std::tuple(e.a.x, e.a.y, e.b.x, e.b.y, e.weight); }

ChangedBox changedBox(std::span<const planar::DirectedEdge> before, std::span<const planar::DirectedEdge> now) {
    std::vector<planar::DirectedEdge> a(before.begin(), before.end()), b(now.begin(), now.end());
    auto less = [](const planar::DirectedEdge& p, const planar::DirectedEdge& q) { return edgeTuple(p) < edgeTuple(q); };
    std::sort(a.begin(), a.end(), less);
    std::sort(b.begin(), b.end(), less);
    ChangedBox box;
    size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        if (j == b.size() || (i < a.size() && less(a[i], b[j]))) box.extend(a[i++]);
        else if (i == a.size() || less(b[j], a[i])) box.extend(b[j++]);
        else ++i, ++j;
    }
    return box;
}

uint64_t keyBits(double v) {
    if (v == 0.0) v = 0.0;  // -0 equals 0
    uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

size_t triangleHash(const WeightedTriangles::Triangle& t) {
    uint64_t h = 0x84222325CBF29CE4ull;
    auto mix = [&](uint64_t v) {
        h ^= v;
        h *= 0x9E3779B97F4A7C15ull;
        h ^= h >> 29;
    };
    for (int k = 0; k < 3; ++k) {
        mix(keyBits(t.x[k]));
        mix(keyBits(t.y[k]));
        mix(keyBits(double(t.in[k])));
    }
    return size_t(h);
}

bool sameCorners(const WeightedTriangles::Triangle& a, const WeightedTriangles::Triangle& b) {
    for (int k = 0; k < 3; ++k)
        if (a.x[k] != b.x[k] || a.y[k] != b.y[k] || a.in[k] != b.in[k]) return false;
    return true;
}

// The kept triangle with the corners of `t`, or null.
const WeightedTriangles::Triangle* findKept(const WeightedTriangles& kept, const WeightedTriangles::Triangle& t) {
    if (kept.slots.empty()) return nullptr;
    const size_t mask = kept.slots.size() - 1;
    for (size_t i = triangleHash(t) & mask; kept.slots[i] != 0; i = (i + 1) & mask) {
        const WeightedTriangles::Triangle& k = kept.triangles[kept.slots[i] - 1];
        if (sameCorners(k, t)) return &k;
    }
    return nullptr;
}

void indexTriangles(WeightedTriangles& kept) {
    size_t capacity = 16;
    while (capacity < 2 * kept.triangles.size()) capacity *= 2;
    kept.slots.assign(capacity, 0);
    const size_t mask = capacity - 1;
    for (size_t t = 0; t < kept.triangles.size(); ++t) {
        size_t i = triangleHash(kept.triangles[t]) & mask;
        while (kept.slots[i] != 0) i = (i + 1) & mask;
        kept.slots[i] = uint32_t(t + 1);
    }
}

void weigh(planar::ShadowMesh& mesh, std::span<const std::vector<planar::DirectedEdge>> outlines,
           std::span<const LightSample> samples, const Light& light, const ReceiverPlane& plane,
           const planar::Snap& snap, planar::FillMode fill, WeightedTriangles* kept, WeightStats* stats) {
    const size_t n = samples.size();
    if (n == 0 || outlines.size() != n) return;
    std::vector<BandedOutline> bands;
    bands.reserve(n);
    for (size_t s = 0; s < n; ++s) bands.emplace_back(outlines[s]);
    const glm::dvec3 emitDir(light.direction());
    const glm::dvec3* emits = light.isArea() ? &emitDir : nullptr;
    const glm::dvec3 emitKey = emits ? emitDir : glm::dvec3(0.0);
    // What the earlier call left applies only to the same fill, emitter and number of samples
    // (the cache drops it when the plane or the samples change).
    const bool reuse = kept && kept->fill == fill && kept->emits == emitKey && kept->outlines.size() == n;
    std::vector<ChangedBox> changed(reuse ? n : 0);
    for (size_t s = 0; s < changed.size(); ++s) changed[s] = changedBox(kept->outlines[s], outlines[s]);
    std::vector<WeightedTriangles::Triangle> made;
    if (kept) made.reserve(mesh.indices.size() / 3);
    // The fill emits every triangle's corners separately; a corner's n weights are computed once
    // per distinct position (about a sixth of the corners) and kept in `weights`.
    CornerIndex corner(mesh.indices.size() / 4);
    std::vector<double> weights;
    weights.reserve(mesh.indices.size() / 4 * (n + 1));
    auto weightsAt = [&](const planar::ShadowVertex& c) -> const double* {
        bool added = false;
        const uint32_t slot = corner.find(c.x, c.y, uint32_t(weights.size() / (n + 1)), &added);
        if (added) {
            glm::dvec3 p = plane.toWorld(snap.toU(c.x), snap.toV(c.y));
            double all = 0;
            for (size_t s = 0; s < n; ++s) {
                weights.push_back(weightTowards(emits, samples[s], p, plane.normal));
                all += weights.back();
            }
            weights.push_back(all);
        }
        return weights.data() + size_t(slot) * (n + 1);
    };
    std::vector<planar::ShadowVertex> out;
    out.reserve(mesh.indices.size());
    std::vector<char> inShadow(n);
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const planar::ShadowVertex* v[3] = {&mesh.vertices[mesh.indices[t]], &mesh.vertices[mesh.indices[t + 1]],
                                            &mesh.vertices[mesh.indices[t + 2]]};
        double cx = (v[0]->x + v[1]->x + v[2]->x) / 3.0, cy = (v[0]->y + v[1]->y + v[2]->y) / 3.0;
        WeightedTriangles::Triangle tri;
        for (int k = 0; k < 3; ++k) tri.x[k] = v[k]->x, tri.y[k] = v[k]->y, tri.in[k] = v[k]->intensity;
        const WeightedTriangles::Triangle* earlier = nullptr;
        if (reuse && std::all_of(changed.begin(), changed.end(), [&](const ChangedBox& b) { return b.outside(cx, cy); }))
            earlier = findKept(*kept, tri);
        if (earlier) {
            for (int k = 0; k < 3; ++k) tri.out[k] = earlier->out[k];
            if (stats) ++stats->trianglesReused;
        } else {
            int count = 0;
            for (size_t s = 0; s < n; ++s) {
                bool in = bands[s].winding(cx, cy) != 0;
                inShadow[s] = in;
                count += in;
            }
            for (int k = 0; k < 3; ++k) {
                const planar::ShadowVertex* c = v[k];
                tri.out[k] = c->intensity;
                // The umbra (every sample) keeps 1 and the lit part 0 whatever the weights.
                if (count > 0 && size_t(count) < n) {
                    const double* w = weightsAt(*c);
                    double all = w[n], shadowed = 0;
                    for (size_t s = 0; s < n; ++s)
                        if (inShadow[s]) shadowed += w[s];
                    // A corner every sample is below the horizon of keeps its count-based value.
                    double share = all > 0 ? shadowed / all : double(count) / double(n);
                    double value = fill == planar::FillMode::Steps ? share
                                                                    : c->intensity * share * double(n) / double(count);
                    tri.out[k] = float(std::clamp(value, 0.0, 1.0));
                }
            }
            if (stats) ++stats->trianglesWeighed;
        }
        for (int k = 0; k < 3; ++k) {
            planar::ShadowVertex o = *v[k];
            o.intensity = tri.out[k];
            out.push_back(o);
        }
        if (kept) made.push_back(tri);
    }
    mesh.vertices = std::move(out);
    mesh.indices.resize(mesh.vertices.size());
    for (size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = uint32_t(i);
    if (kept) {
        kept->fill = fill;
        kept->emits = emitKey;
        kept->outlines.assign(outlines.begin(), outlines.end());
        kept->triangles = std::move(made);
        indexTriangles(*kept);
    }
}

}  // namespace

size_t WeightedTriangles::bytes() const {
    size_t b = sizeof(*this) + outlines.capacity() * sizeof(outlines[0]) + triangles.capacity() * sizeof(Triangle) +
               slots.capacity() * sizeof(uint32_t);
    for (const auto& o : outlines) b += o.capacity() * sizeof(planar::DirectedEdge);
    return b;
}

void WeightedTriangles::clear() { *this = WeightedTriangles{}; }

void weighShadowMesh(planar::ShadowMesh& mesh, std::span<const std::vector<planar::DirectedEdge>> outlines,
                     std::span<const LightSample> samples, const Light& light, const ReceiverPlane& plane,
                     const planar::Snap& snap, planar::FillMode fill, WeightStats* stats) {
    weigh(mesh, outlines, samples, light, plane, snap, fill, nullptr, stats);
}

void weighShadowMesh(planar::ShadowMesh& mesh, std::span<const std::vector<planar::DirectedEdge>> outlines,
                     std::span<const LightSample> samples, const Light& light, const ReceiverPlane& plane,
                     const planar::Snap& snap, planar::FillMode fill, WeightedTriangles& kept, WeightStats* stats) {
    weigh(mesh, outlines, samples, light, plane, snap, fill, &kept, stats);
}

}  // namespace ss
