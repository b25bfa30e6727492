// How the CPU reference box filters (brute force, SAT, N-Buffers, mipmaps) compute their means.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "filters/box_filter.h"

#include <algorithm>
#include <cmath>

namespace ss::filters {

namespace {
// Length of [a, b] ∩ [i, i + 1].
double overlap(double a, double b, int i) {
    return std::max(0.0, std::min(b, double(i + 1)) - std::max(a, double(i)));
}
float lerp(float a, float b, float t) { return a + (b - a) * t; }
}  // namespace

double boxBrute(const Plane& p, double x0, double y0, double x1, double y1) {
    double area = (x1 - x0) * (y1 - y0);
    if (area <= 0.0) return 0.0;
    double sum = 0.0;
    int i0 = std::max(0, int(std::floor(x0))), i1 = std::min(p.width - 1, int(std::floor(x1)));
    int j0 = std::max(0, int(std::floor(y0))), j1 = std::min(p.height - 1, int(std::floor(y1)));
    for (int j = j0; j <= j1; ++j) {
        double wy = overlap(y0, y1, j);
        if (wy <= 0.0) continue;
        for (int i = i0; i <= i1; ++i) sum += wy * overlap(x0, x1, i) * p.at(i, j);
    }
    return sum / area;
}

// ---- summed-area table -------------------------------------------------------------------

float SummedAreaTable::F(int i, int j) const {
    i = std::clamp(i, 0, width);
    j = std::clamp(j, 0, height);
    return table[size_t(j) * (width + 1) + i];
}

SummedAreaTable SummedAreaTable::build(const Plane& p) {
    SummedAreaTable s;
    s.width = p.width;
    s.height = p.height;
    s.table.assign(size_t(p.width + 1) * (p.height + 1), 0.0f);
    for (int j = 1; j <= p.height; ++j) {
        float row = 0.0f;
        for (int i = 1; i <= p.width; ++i) {
            row += p.at(i - 1, j - 1);
            s.table[size_t(j) * (p.width + 1) + i] = s.table[size_t(j - 1) * (p.width + 1) + i] + row;
        }
    }
    return s;
}

float SummedAreaTable::box(float x0, float y0, float x1, float y1) const {
    float area = (x1 - x0) * (y1 - y0);
    if (!(area > 0.0f)) return 0.0f;
    // Clamp to the table: outside the texture nothing is added, the area stays the full box.
    auto cx = [&](float x) { return std::clamp(x, 0.0f, float(width)); };
    auto cy = [&](float y) { return std::clamp(y, 0.0f, float(height)); };
    float ax = cx(x0), bx = cx(x1), ay = cy(y0), by = cy(y1);
    int ia = std::min(int(std::floor(ax)), width - 1), ib = std::min(int(std::floor(bx)), width - 1);
    int ja = std::min(int(std::floor(ay)), height - 1), jb = std::min(int(std::floor(by)), height - 1);
    float fa = ax - ia, fb = bx - ib, ga = ay - ja, gb = by - jb;
    // Sum over x in [ax, bx] of the texels below row j: exact integer differences, then weights.
    auto strip = [&](int j) {
        return (F(ib, j) - F(ia, j)) + fb * (F(ib + 1, j) - F(ib, j)) - fa * (F(ia + 1, j) - F(ia, j));
    };
    float sa = strip(ja), sa1 = strip(ja + 1), sb = strip(jb), sb1 = strip(jb + 1);
    float sum = (sb - sa) + gb * (sb1 - sb) - ga * (sa1 - sa);
    return sum / area;
}

// ---- N-Buffers ---------------------------------------------------------------------------

NBuffer NBuffer::build(const Plane& p) {
    NBuffer n;
    n.width = p.width;
    n.height = p.height;
    int count = 1;
    while ((1 << (count - 1)) < std::max(p.width, p.height)) ++count;
    n.levels.push_back(p);
    for (int l = 1; l < count; ++l) {
        const Plane& prev = n.levels.back();
        int h = 1 << (l - 1);
        Plane next(p.width, p.height);
        for (int j = 0; j < p.height; ++j)
            for (int i = 0; i < p.width; ++i)
                next.at(i, j) = 0.25f * (prev.at(i, j) + prev.at(i + h, j) + prev.at(i, j + h) +
                                         prev.at(i + h, j + h));
        n.levels.push_back(std::move(next));
    }
    return n;
}

float NBuffer::sample(int level, float x, float y) const {
    const Plane& p = levels[size_t(std::clamp(level, 0, int(levels.size()) - 1))];
    float fx = x - 0.5f, fy = y - 0.5f;
    int i = int(std::floor(fx)), j = int(std::floor(fy));
    float tx = fx - i, ty = fy - j;
    return lerp(lerp(p.at(i, j), p.at(i + 1, j), tx), lerp(p.at(i, j + 1), p.at(i + 1, j + 1), tx), ty);
}

namespace {
// The N-Buffer response for a square box of side s centred at (cx, cy).
float nbufferSquare(const NBuffer& n, float cx, float cy, float s) {
    int top = int(n.levels.size()) - 1;
    float ls = std::log2(std::max(s, 1.0f));
    int l = std::min(int(std::floor(ls)), top);
    auto at = [&](int level) {
        float half = 0.5f * float(1 << level);
        // Texel i of level l averages [i, i + 2^l): its box is centred at i + 2^(l-1).
        return n.sample(level, cx - half + 0.5f, cy - half + 0.5f);
    };
    if (l >= top) return at(top);
    float size = float(1 << l);
    float t = std::clamp((s - size) / size, 0.0f, 1.0f);
    return lerp(at(l), at(l + 1), t);
}
}  // namespace

float NBuffer::box(float cx, float cy, float w, float h) const {
    float s = std::min(w, h), L = std::max(w, h);
    int probes = std::clamp(int(std::ceil(L / std::max(s, 1e-6f) - 1e-3f)), 1, 8);
    float sum = 0.0f;
    for (int k = 0; k < probes; ++k) {
        float offset = (float(k) + 0.5f) * L / float(probes) - 0.5f * L;
        sum += w >= h ? nbufferSquare(*this, cx + offset, cy, s) : nbufferSquare(*this, cx, cy + offset, s);
    }
    return sum / float(probes);
}

// ---- mipmaps -----------------------------------------------------------------------------

Mipmap Mipmap::build(const Plane& p) {
    Mipmap m;
    m.levels.push_back(p);
    while (m.levels.back().width > 1 || m.levels.back().height > 1) {
        const Plane& prev = m.levels.back();
        Plane next(std::max(1, prev.width / 2), std::max(1, prev.height / 2));
        for (int j = 0; j < next.height; ++j)
            for (int i = 0; i < next.width; ++i) {
                int i0 = std::min(2 * i, prev.width - 1), i1 = std::min(2 * i + 1, prev.width - 1);
                int j0 = std::min(2 * j, prev.height - 1), j1 = std::min(2 * j + 1, prev.height - 1);
                next.at(i, j) = 0.25f * (prev.at(i0, j0) + prev.at(i1, j0) + prev.at(i0, j1) + prev.at(i1, j1));
            }
        m.levels.push_back(std::move(next));
    }
    return m;
}

float Mipmap::bilinear(int level, float u, float v) const {
    const Plane& p = levels[size_t(std::clamp(level, 0, int(levels.size()) - 1))];
    float fx = u * p.width - 0.5f, fy = v * p.height - 0.5f;
    int i = int(std::floor(fx)), j = int(std::floor(fy));
    float tx = fx - i, ty = fy - j;
    return lerp(lerp(p.at(i, j), p.at(i + 1, j), tx), lerp(p.at(i, j + 1), p.at(i + 1, j + 1), tx), ty);
}

float Mipmap::box(float cx, float cy, float w, float h) const {
    const Plane& base = levels.front();
    float s = std::max(std::min(w, h), 1e-6f), L = std::max(w, h);
    int probes = std::clamp(int(std::ceil(L / s - 1e-3f)), 1, 16);
    float lod = std::clamp(std::log2(std::max(s, L / 16.0f)), 0.0f, float(levels.size() - 1));
    int l0 = int(std::floor(lod));
    float t = lod - l0;
    float sum = 0.0f;
    for (int k = 0; k < probes; ++k) {
        float offset = (float(k) + 0.5f) * L / float(probes) - 0.5f * L;
        float x = w >= h ? cx + offset : cx, y = w >= h ? cy : cy + offset;
        float u = x / base.width, v = y / base.height;
        sum += lerp(bilinear(l0, u, v), bilinear(l0 + 1, u, v), t);
    }
    return sum / float(probes);
}

}  // namespace ss::filters
