// How n hard-shadow outlines are merged in a second sweep into nested rings: ring k bounds
// the points that k or more samples see in shadow, and carries intensity (k-1)/(n-1).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <span>
#include <vector>

#include "planar/outline.h"

namespace ss::planar {

// All n outlines as one edge set: its winding number at a point is how many samples see the
// point in shadow (each outline winds once around its own shadow).
std::vector<DirectedEdge> mergeOutlines(std::span<const std::vector<DirectedEdge>> outlines);

struct Ring {
    int level = 0;           // k: the boundary of {count >= k}
    float intensity = 0.0f;  // (k-1)/(n-1); 1 for a single sample
    std::vector<Chain> chains;
};

// Rings 1..n, outermost first. Ring k+1 lies inside ring k by construction (level sets).
std::vector<Ring> buildRings(std::span<const DirectedEdge> merged, int samples);

// The intensity a ring of level k carries.
float ringIntensity(int level, int samples);

}  // namespace ss::planar
