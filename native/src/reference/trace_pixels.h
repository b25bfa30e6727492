// What the reference's V is at a chosen list of pixels (the sparse exact check behind `auto`).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "reference/trace_scene.h"

namespace ss {

struct PixelVisibility {
    int x = 0, y = 0;
    float visibility = 1.0f;
    bool inMask = false;  // a receiving surface the light reaches (the reference's mask)
};

// The reference's V and mask at each listed pixel, exactly as renderReference computes them for
// the same (seed, samples): the same camera span, the same stratified irradiance-weighted light
// samples of SampleSequence(seed, x, y). Pixels outside the image are refused.
std::vector<PixelVisibility> tracePixels(const TraceScene& trace, const Scene& scene, int lightIndex,
                                         const std::vector<std::pair<int, int>>& pixels, int samples,
                                         uint32_t seed);

}  // namespace ss
