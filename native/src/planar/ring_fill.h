// How the paper's ring fill (fill=rings) triangulates the penumbra: each strip between two
// neighbouring rings is walked with triangles whose corners lie on the rings themselves.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <span>

#include "planar/penumbra_fill.h"

namespace ss::planar {

struct RingFillStats {
    size_t stripTriangles = 0;    // corners on both rings
    size_t bayTriangles = 0;      // every corner on the same one ring: flat
    size_t leakTriangles = 0;     // corners on one ring and crossing points
    size_t crossingVertices = 0;  // strip corners on both rings: the mean of the two
    size_t roundedStrips = 0;     // pieces tiled up to a sliver where rounded chains cross
    size_t fallbackStrips = 0;    // strips (or the umbra) the walk could not finish: trapezoids
};

// The paper's fill. Ring k (boundary of count >= k, intensity (k-1)/(n-1)) and ring k+1 bound
// the strip {count == k}; its boundary, linked into closed chains, is the two rings cut and
// rejoined where they meet. Each strip (holes bridged in) is cut into triangles with corners on
// its chains only: strip triangles (corners on both rings) first, the shortest new diagonal
// first, so the walk advances on whichever ring's next point is nearer; what is left are bays
// (one ring only, flat) and the paper's leak triangles (one ring and crossing points). A
// triangle is only cut when no other chain point lies in it, so no two overlap. Corners: their
// ring's intensity; a point on both rings the mean of the two (the paper's crossing-point
// rule). Umbra (count n): walked the same way, flat 1 (the paper takes the sweep's
// trapezoids; the same rounded chain on both sides of ring n leaves no sliver between them).
// Triangles counter-clockwise.
ShadowMesh fillRings(std::span<const DirectedEdge> merged, int samples, RingFillStats* stats = nullptr);

}  // namespace ss::planar
