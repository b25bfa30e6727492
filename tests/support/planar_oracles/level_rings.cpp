// How the tests' level-set rings are extracted: one region boundary per level, linked.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar_oracles/level_rings.h"

#include "planar/rings.h"

namespace ss::planar {

std::vector<Ring> buildRings(std::span<const DirectedEdge> mergedEdges, int samples) {
    std::vector<SweepSegment> merged = toSweepSegments(mergedEdges);
    std::vector<Ring> rings;
    for (int k = 1; k <= samples; ++k) {
        Ring r;
        r.level = k;
        r.intensity = ringIntensity(k, samples);
        r.chains = linkChains(regionBoundary(merged, [k](int w) { return w >= k; }));
        rings.push_back(std::move(r));
    }
    return rings;
}

}  // namespace ss::planar
