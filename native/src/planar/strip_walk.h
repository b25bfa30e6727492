// How a polygon with holes (one strip of the ring fill) is cut into triangles whose corners are
// its own points, triangles spanning two rings first.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "planar/predicates.h"

namespace ss::planar {

struct WalkPoint {
    IPoint p;
    uint8_t rings = 0;  // which rings the point lies on, one bit each
};
using WalkTriangle = std::array<WalkPoint, 3>;

// `outer` counter-clockwise, `holes` clockwise and inside it (touching allowed). Holes are
// bridged to the outer chain from their leftmost points, as ear-clipping triangulators do. Then
// candidates whose three corners share no ring bit go first, the shortest new diagonal first;
// a triangle is cut only when it turns counter-clockwise and no other point lies in it or on
// its sides (a point at one of its corners only when its own wedge reaches into it), so no two
// triangles overlap. False when the walk gets stuck (a polygon that is not weakly simple).
bool walkPolygon(std::span<const WalkPoint> outer, std::span<const std::vector<WalkPoint>> holes,
                 std::vector<WalkTriangle>* out);

}  // namespace ss::planar
