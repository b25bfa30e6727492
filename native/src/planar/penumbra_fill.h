// How the merged outlines become the shadow mesh: triangles whose vertices carry shadow
// intensity, penumbra strips spanning adjacent rings, bays and umbra with plain triangles.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "planar/rings.h"
#include "planar/trapezoids.h"

namespace ss::planar {

// smooth: the merged sweep's trapezoids, Gouraud between ring intensities; steps: count / n,
// flat per region; rings: the paper's strips walked between neighbouring rings (ring_fill.h).
enum class FillMode { Smooth, Steps, Rings };

struct ShadowVertex {
    double x = 0, y = 0;      // grid coordinates
    float intensity = 0.0f;   // 0 = lit, 1 = umbra; V = 1 - intensity
};

struct ShadowMesh {
    std::vector<ShadowVertex> vertices;
    std::vector<uint32_t> indices;  // three per triangle, counter-clockwise
    size_t umbraTriangles = 0;
    size_t penumbraTriangles = 0;
    double umbraArea = 0.0;     // grid units squared
    double shadowArea = 0.0;    // count >= 1
    size_t ringFallbacks = 0;   // fill=rings: strips filled with trapezoids (ring_fill.h)
};

// `merged`: mergeOutlines() of the n samples' closed hard outlines.
ShadowMesh fillShadow(std::span<const DirectedEdge> merged, int samples, FillMode mode);

}  // namespace ss::planar
