// Which triangles of a mesh may cover a pixel centre of a pass's rectangle: the camera pass draws
// only those, so a 1M-triangle scene seen at 240x135 draws a few percent of its triangles.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene_cache/moved_region.h"

namespace ss {

// A pass as the GPU draws it: vertices placed by objectToWorld (when transformed) and
// worldToClip, width x height pixels, of which `rect` (GL orientation) is drawn.
struct CoverageView {
    glm::mat4 worldToClip{1.0f};
    bool transformed = false;
    glm::mat4 objectToWorld{1.0f};
    int width = 0, height = 0;
    PixelRect rect;
};

// The test is conservative: a triangle it leaves out has no pixel centre of the rectangle inside
// it (edges included) nor is it clipped into one, whatever the rounding of the GPU's float
// transform, perspective divide and sub-pixel snapping, each bounded per vertex from the
// magnitudes of the terms it sums. So a pass drawn from the listed triangles, in their order,
// is the pass drawn from every triangle bit for bit (depth ties resolve by the same order).
// Vertices are projected when a triangle first uses them; the scratch is kept between calls.
class CoveringTriangles {
public:
    // Starts a mesh (its coordinates as uploaded: object space when view.transformed).
    void beginMesh(const CoverageView& view, const std::vector<glm::vec3>& positions);
    // Appends to `out`, in order, the triangles of [first, first + count) that may cover a pixel
    // centre of the rectangle.
    void append(const std::vector<glm::uvec3>& triangles, uint32_t first, uint32_t count,
                std::vector<uint32_t>& out);

private:
    // A projected vertex: window position (GL orientation), the bound of its error in pixels and
    // which clip planes it is certainly outside. 16 bytes: the scratch holds one per vertex of
    // the largest mesh.
    struct Vertex {
        float x = 0.0f, y = 0.0f, error = 0.0f;
        uint32_t flags = 0;
    };
    const Vertex& vertex(uint32_t index);
    void project(uint32_t index, Vertex& out) const;
    CoverageView view_;
    const std::vector<glm::vec3>* positions_ = nullptr;
    glm::dmat4 toClip_{1.0};           // object (or world) coordinates to clip
    glm::dmat4 magnitudeToClip_{1.0};  // |worldToClip| |objectToWorld|: bounds the GPU's rounding
    std::vector<Vertex> vertices_;
    std::vector<uint32_t> stamps_;  // == generation_: vertices_[i] holds this mesh's projection
    uint32_t generation_ = 0;
};

}  // namespace ss
