// How the bucket grid over the shadow triangles is built and queried.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/lookup.h"

#include <algorithm>
#include <cmath>

namespace ss {

ShadowLookup::ShadowLookup(const planar::ShadowMesh& mesh) : mesh_(mesh) {
    size_t tris = mesh.indices.size() / 3;
    if (tris == 0) return;
    double lx = 1e300, ly = 1e300, hx = -1e300, hy = -1e300;
    for (const auto& v : mesh.vertices) {
        lx = std::min(lx, v.x), ly = std::min(ly, v.y), hx = std::max(hx, v.x), hy = std::max(hy, v.y);
    }
    // About two triangles per cell on average.
    double area = std::max((hx - lx) * (hy - ly), 1.0);
    cell_ = std::max(std::sqrt(2.0 * area / double(tris)), 1.0);
    nx_ = std::clamp(int((hx - lx) / cell_) + 1, 1, 4096);
    ny_ = std::clamp(int((hy - ly) / cell_) + 1, 1, 4096);
    cell_ = std::max((hx - lx) / nx_, (hy - ly) / ny_) * (1 + 1e-9) + 1e-9;
    x0_ = lx, y0_ = ly;
    std::vector<uint32_t> count(size_t(nx_) * ny_ + 1, 0);
    auto range = [&](size_t t, int* i0, int* i1, int* j0, int* j1) {
        double ax = 1e300, ay = 1e300, bx = -1e300, by = -1e300;
        for (int k = 0; k < 3; ++k) {
            const auto& v = mesh.vertices[mesh.indices[3 * t + k]];
            ax = std::min(ax, v.x), ay = std::min(ay, v.y), bx = std::max(bx, v.x), by = std::max(by, v.y);
        }
        *i0 = std::clamp(int((ax - x0_) / cell_), 0, nx_ - 1);
        *i1 = std::clamp(int((bx - x0_) / cell_), 0, nx_ - 1);
        *j0 = std::clamp(int((ay - y0_) / cell_), 0, ny_ - 1);
        *j1 = std::clamp(int((by - y0_) / cell_), 0, ny_ - 1);
    };
    for (size_t t = 0; t < tris; ++t) {
        int i0, i1, j0, j1;
        range(t, &i0, &i1, &j0, &j1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) ++count[size_t(j) * nx_ + i + 1];
    }
    for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    start_ = count;
    items_.resize(count.back());
    std::vector<uint32_t> fill(count.begin(), count.end() - 1);
    for (size_t t = 0; t < tris; ++t) {
        int i0, i1, j0, j1;
        range(t, &i0, &i1, &j0, &j1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) items_[fill[size_t(j) * nx_ + i]++] = uint32_t(t);
    }
}

float ShadowLookup::intensity(double x, double y) const {
    if (nx_ == 0) return 0.0f;
    int i = int(std::floor((x - x0_) / cell_)), j = int(std::floor((y - y0_) / cell_));
    if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return 0.0f;
    size_t c = size_t(j) * nx_ + i;
    for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
        size_t t = items_[k];
        const auto& a = mesh_.vertices[mesh_.indices[3 * t]];
        const auto& b = mesh_.vertices[mesh_.indices[3 * t + 1]];
        const auto& d = mesh_.vertices[mesh_.indices[3 * t + 2]];
        double det = (b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x);
        if (!(det > 0)) continue;
        double l1 = ((x - a.x) * (d.y - a.y) - (y - a.y) * (d.x - a.x)) / det;
        double l2 = ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)) / det;
        double l0 = 1 - l1 - l2;
        // Points on a shared side belong to either triangle: both give the same value there.
        if (l0 >= 0 && l1 >= 0 && l2 >= 0)
            return std::clamp(float(l0 * a.intensity + l1 * b.intensity + l2 * d.intensity), 0.0f, 1.0f);
    }
    return 0.0f;
}

}  // namespace ss
