// How outlines are merged and what intensity each ring carries.
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

}  // namespace ss::planar
