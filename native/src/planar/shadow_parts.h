// Which pieces of a merged edge set can be filled apart: the edges of shadow regions that do not
// touch, so that a light's shadow filled once keeps the pieces an edit did not reach.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <span>
#include <vector>

#include "planar/sweep_line.h"

namespace ss::planar {

// Lexicographic by a, b, weight: the canonical order of a part's edges.
bool edgeLess(const DirectedEdge& p, const DirectedEdge& q);
bool sameEdges(std::span<const DirectedEdge> p, std::span<const DirectedEdge> q);

// The merged edges (a sum of closed cycles) split into parts such that the closed regions where
// the winding number is not 0 of two different parts never meet: every trapezoid of the fill
// lies between edges of one part, and a part's fill does not depend on the others. Each part's
// edges are in edgeLess order and the parts ordered by their first edge, so the split of the
// same edges is the same whatever their order. The split is conservative: regions closer than a
// cell of a grid of about kPartCells² over the edges share a part.
std::vector<std::vector<DirectedEdge>> separateShadowParts(std::span<const DirectedEdge> merged);

inline constexpr int kPartCells = 512;

}  // namespace ss::planar
