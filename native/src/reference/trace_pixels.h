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
    bool centreVisible = true;  // lightCentreVisible there: outside the light centre's hard shadow
    int mesh = -1;              // the receiving mesh the pixel sees (scene.meshes() index), -1 none
};

// The reference's V and mask at each listed pixel, exactly as renderReference computes them for
// the same (seed, samples): the same camera span, the same stratified irradiance-weighted light
// samples of SampleSequence(seed, x, y). Pixels outside the image are refused.
// With `adaptive`, each pixel takes the adaptive reference's rounds instead (sampleAdaptively:
// no guard band, at most adaptive->maxSamples): the same V where a pixel took every sample,
// within the error target elsewhere, at a fraction of the rays where the pixel is decided early.
struct AdaptiveSampling;  // reference/adaptive_sampling.h
std::vector<PixelVisibility> tracePixels(const TraceScene& trace, const Scene& scene, int lightIndex,
                                         const std::vector<std::pair<int, int>>& pixels, int samples,
                                         uint32_t seed, const AdaptiveSampling* adaptive = nullptr);

}  // namespace ss
