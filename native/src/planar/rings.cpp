// How outlines are merged and their level-set rings extracted.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "planar/rings.h"

namespace ss::planar {

std::vector<DirectedEdge> mergeOutlines(std::span<const std::vector<DirectedEdge>> outlines) {
    std::vector<DirectedEdge> all;
    for (const auto& o : outlines) all.insert(all.end(), o.begin(), o.end());
    return all;
}

float ringIntensity(int level, int samples) {
    if (samples <= 1) return 1.0f;
    return float(level - 1) / float(samples - 1);
}

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
