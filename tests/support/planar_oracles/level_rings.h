// What the rings are by definition, for the tests: ring k is the boundary of the points k or
// more samples see in shadow, extracted one level at a time (test support, not shipped; the
// product's ring fill gets every strip from one sweep, planar/ring_fill.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <span>
#include <vector>

#include "planar/outline.h"

namespace ss::planar {

struct Ring {
    int level = 0;           // k: the boundary of {count >= k}
    float intensity = 0.0f;  // (k-1)/(n-1); 1 for a single sample
    std::vector<Chain> chains;
};

// Rings 1..n, outermost first, each from its own sweep of the merged outlines.
std::vector<Ring> buildRings(std::span<const DirectedEdge> merged, int samples);

}  // namespace ss::planar
