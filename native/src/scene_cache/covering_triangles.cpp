// How a mesh's triangles are tested for covering a pixel centre of a pass (rules in
// covering_triangles.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/covering_triangles.h"

#include <algorithm>
#include <cmath>

namespace ss {

namespace {

// Vertex flags: certainly outside the clip plane x < w, x > -w, y < w, y > -w, z < w, z > -w;
// kUnplaced: no trustworthy window position (at or behind the eye, or an error bound too large
// to be useful), so triangles using it are kept unless all three are outside one plane.
constexpr uint32_t kOutside = 63u, kUnplaced = 64u;
// The GPU's float transform (two matrix products, up to eight roundings a component) errs by
// less than this many times the sum of the magnitudes of the terms it adds: 2^-19 is about 32
// float roundings.
constexpr double kRelative = 1.0 / 524288.0;
// Sub-pixel snapping of window positions (llvmpipe: 1/256 pixel) and the rounding of the
// viewport transform, in pixels, on top of the projected error.
constexpr double kSnap = 1.0 / 128.0;
// A vertex placed less precisely than this (pixels) is not placed at all: its triangles are kept.
constexpr double kUsefulError = 0.25;

glm::dmat4 absolute(const glm::dmat4& m) {
    glm::dmat4 a;
    for (int c = 0; c < 4; ++c) a[c] = glm::abs(m[c]);
    return a;
}

// floor and ceil of a value above -4 (SSE2 has no rounding instruction: truncation instead of a
// libm call).
int floorOf(float v) { return int(v + 4.0f) - 4; }
int ceilOf(float v) {
    const int f = floorOf(v);
    return float(f) < v ? f + 1 : f;
}

}  // namespace

void CoveringTriangles::beginMesh(const CoverageView& view, const std::vector<glm::vec3>& positions) {
    view_ = view;
    positions_ = &positions;
    const glm::dmat4 worldToClip(view.worldToClip);
    if (view.transformed) {
        const glm::dmat4 objectToWorld(view.objectToWorld);
        toClip_ = worldToClip * objectToWorld;
        magnitudeToClip_ = absolute(worldToClip) * absolute(objectToWorld);
    } else {
        toClip_ = worldToClip;
        magnitudeToClip_ = absolute(worldToClip);
    }
    if (vertices_.size() < positions.size()) {
        vertices_.resize(positions.size());
        stamps_.resize(positions.size(), 0);
    }
    if (++generation_ == 0) {  // wrapped: no stamp may match by accident
        std::fill(stamps_.begin(), stamps_.end(), 0u);
        generation_ = 1;
    }
}

void CoveringTriangles::project(uint32_t index, Vertex& out) const {
    const glm::dvec4 p(glm::dvec3((*positions_)[index]), 1.0);
    // The GPU places the vertex in two products (object to world, world to clip); the sums of
    // the magnitudes of their terms are bounded by |worldToClip| |objectToWorld| |p|.
    const glm::dvec4 clip = toClip_ * p;
    const glm::dvec4 error = kRelative * (magnitudeToClip_ * glm::abs(p));
    out.flags = 0;
    if (clip.x - clip.w > error.x + error.w) out.flags |= 1u;
    if (-clip.x - clip.w > error.x + error.w) out.flags |= 2u;
    if (clip.y - clip.w > error.y + error.w) out.flags |= 4u;
    if (-clip.y - clip.w > error.y + error.w) out.flags |= 8u;
    if (clip.z - clip.w > error.z + error.w) out.flags |= 16u;
    if (-clip.z - clip.w > error.z + error.w) out.flags |= 32u;
    if (!(clip.w > 4.0 * error.w) || !(clip.w > 0.0)) {
        out.flags |= kUnplaced;
        return;
    }
    // Window position and how far the GPU's may lie from it: the error of x / w from those of
    // x and w, scaled to pixels, plus snapping.
    const double halfW = 0.5 * view_.width, halfH = 0.5 * view_.height;
    const double nx = clip.x / clip.w, ny = clip.y / clip.w;
    const double wLow = clip.w - error.w;
    const double ex = halfW * (error.x + std::abs(nx) * error.w) / wLow;
    const double ey = halfH * (error.y + std::abs(ny) * error.w) / wLow;
    const double x = (nx + 1.0) * halfW, y = (ny + 1.0) * halfH;
    const double e = std::max(ex, ey) + kRelative * (std::abs(x) + std::abs(y) + halfW + halfH) + kSnap;
    if (!(e < kUsefulError) || !std::isfinite(x) || !std::isfinite(y)) {
        out.flags |= kUnplaced;
        return;
    }
    out.x = float(x);
    out.y = float(y);
    out.error = float(e);
}

const CoveringTriangles::Vertex& CoveringTriangles::vertex(uint32_t index) {
    Vertex& v = vertices_[index];
    if (stamps_[index] != generation_) {
        project(index, v);
        stamps_[index] = generation_;
    }
    return v;
}

void CoveringTriangles::append(const std::vector<glm::uvec3>& triangles, uint32_t first, uint32_t count,
                               std::vector<uint32_t>& out) {
    // A centre of a rectangle this many pixels or more is left to the rasteriser (the triangle
    // is kept): larger triangles nearly always cover one.
    constexpr int kMaxTested = 4;
    const uint32_t end = first + count;
    // Positions are clamped a little beyond the rectangle before rounding to whole pixels.
    const PixelRect& r = view_.rect;
    const float left = float(r.x0) - 2.0f, right = float(r.x1) + 1.0f;
    const float bottom = float(r.y0) - 2.0f, top = float(r.y1) + 1.0f;
    for (uint32_t t = first; t < end; ++t) {
        const glm::uvec3& tri = triangles[t];
        const Vertex& a = vertex(tri.x);
        const Vertex& b = vertex(tri.y);
        const Vertex& c = vertex(tri.z);
        if (a.flags & b.flags & c.flags & kOutside) continue;
        if ((a.flags | b.flags | c.flags) & kUnplaced) {
            out.push_back(t);
            continue;
        }
        // The snapped triangle lies inside the bounding box of its vertices' error squares: the
        // pixel centres k + 0.5 of the rectangle in it have k in [x0, x1] x [y0, y1].
        const float d = std::max({a.error, b.error, c.error});
        const int x0 = std::max(ceilOf(std::max(std::min({a.x, b.x, c.x}) - 0.5f - d, left)), r.x0);
        const int x1 = std::min(floorOf(std::min(std::max({a.x, b.x, c.x}) - 0.5f + d, right)), r.x1 - 1);
        const int y0 = std::max(ceilOf(std::max(std::min({a.y, b.y, c.y}) - 0.5f - d, bottom)), r.y0);
        const int y1 = std::min(floorOf(std::min(std::max({a.y, b.y, c.y}) - 0.5f + d, top)), r.y1 - 1);
        if (x0 > x1 || y0 > y1) continue;
        if ((x1 - x0 + 1) * (y1 - y0 + 1) >= kMaxTested + 1) {
            out.push_back(t);
            continue;
        }
        // Edge functions at each candidate centre, with margins for vertices that move by up
        // to `d` in x and y: |E' - E| <= d (2 |q - a|_1 + |b - a|_1 + 4 d) for the edge a->b.
        // Either orientation counts (the pass draws both faces).
        const glm::vec2 pa(a.x, a.y), pb(b.x, b.y), pc(c.x, c.y);
        const glm::vec2 ab = pb - pa, bc = pc - pb, ca = pa - pc;
        const float lab = std::abs(ab.x) + std::abs(ab.y), lbc = std::abs(bc.x) + std::abs(bc.y),
                    lca = std::abs(ca.x) + std::abs(ca.y);
        bool covered = false;
        for (int y = y0; y <= y1 && !covered; ++y)
            for (int x = x0; x <= x1 && !covered; ++x) {
                const glm::vec2 q(float(x) + 0.5f, float(y) + 0.5f);
                const glm::vec2 qa = q - pa, qb = q - pb, qc = q - pc;
                const float e0 = ab.x * qa.y - ab.y * qa.x;
                const float e1 = bc.x * qb.y - bc.y * qb.x;
                const float e2 = ca.x * qc.y - ca.y * qc.x;
                const float m0 = d * (2.0f * (std::abs(qa.x) + std::abs(qa.y)) + lab + 4.0f * d);
                const float m1 = d * (2.0f * (std::abs(qb.x) + std::abs(qb.y)) + lbc + 4.0f * d);
                const float m2 = d * (2.0f * (std::abs(qc.x) + std::abs(qc.y)) + lca + 4.0f * d);
                covered = (e0 >= -m0 && e1 >= -m1 && e2 >= -m2) || (e0 <= m0 && e1 <= m1 && e2 <= m2);
            }
        if (covered) out.push_back(t);
    }
}

}  // namespace ss
