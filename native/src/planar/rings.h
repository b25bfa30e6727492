// How n hard-shadow outlines are merged for the second sweep, whose count field's level sets
// are the rings: ring k bounds the points that k or more samples see in shadow, and carries
// intensity (k-1)/(n-1).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <span>
#include <vector>

#include "planar/outline.h"

namespace ss::planar {

// All n outlines as one edge set: its winding number at a point is how many samples see the
// point in shadow (each outline winds once around its own shadow).
std::vector<DirectedEdge> mergeOutlines(std::span<const std::vector<DirectedEdge>> outlines);

// The intensity a ring of level k carries.
float ringIntensity(int level, int samples);

}  // namespace ss::planar
