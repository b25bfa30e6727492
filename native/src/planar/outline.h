// How the boundary of a winding-number region is found (the hard-shadow outline) and linked
// into closed chains, holes kept.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <span>
#include <vector>

#include "planar/sweep_line.h"

namespace ss::planar {

// Which winding numbers belong to the region (hard shadow: w >= 1).
using RegionFn = std::function<bool(int winding)>;

// The region's boundary as directed edges (region on the right), each a maximal run of one
// input segment; crossing points are rounded to the nearest grid point (the only rounding in
// the planar core). Vertical boundary pieces are omitted: no slab's winding depends on them,
// and linkChains() restores them.
std::vector<DirectedEdge> regionBoundary(std::span<const SweepSegment> segments, const RegionFn& inside);

// One closed chain: vertices in order, the last connects back to the first.
using Chain = std::vector<IPoint>;

// Links boundary edges (vertical connectors restored) into closed chains. Outer boundaries
// run clockwise, holes counter-clockwise. Where the boundary meets itself, each visit bounds
// one wedge of the region, so a chain touches itself (or another) without crossing.
// Vertices where a chain goes straight on are dropped unless `keepStraight`.
std::vector<Chain> linkChains(std::span<const DirectedEdge> boundary, bool keepStraight = false);

// Twice the signed area (counter-clockwise positive), exact.
i128 twiceSignedArea(const Chain& chain);
// The area a set of chains encloses with the region on the right, in grid units squared.
double regionArea(std::span<const Chain> chains);

// Adds the vertical pieces regionBoundary() leaves out: along each grid column the running
// out-minus-in balance from the bottom says how many run between consecutive unbalanced
// points, and which way. The result is a set of closed cycles.
void addVerticalConnectors(std::vector<DirectedEdge>* boundary);

// The hard shadow of one sample: the outline of winding >= 1 of its projected directed edges,
// closed (vertical pieces included).
std::vector<DirectedEdge> hardOutline(std::span<const DirectedEdge> projected);

}  // namespace ss::planar
