// How good a method's image is expected to be: its error against the reference on a sparse set
// of pixels traced exactly (what `auto` picks by and what every result's estimate comes from).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "reference/trace_pixels.h"
#include "reference/trace_scene.h"

namespace ss {

// How many pixels the check traces unless told: one in 16, at least 4096 and at most 65536. A
// method's error is heavy-tailed (a thin line of pixels off by 1 at a contact or a terminator),
// and at 4096 pixels of a 512x512 image one such pixel more or less moved an estimate by half;
// at one in 16 the spread over seeds stays within about 5 %.
int sparseCheckDefaultPixels(int width, int height);

// The reference's V at about `pixelCount` pixels, one per cell of a grid over the image at a
// place drawn from (seed, cell): stratified, so the sample follows the image's area, and the same
// for the same seed. Traced with the reference's own samples (kReferenceDefaultSamples unless
// `samples` > 0) and seed, so on these pixels it equals the reference image of that seed.
struct SparseCheck {
    std::vector<PixelVisibility> truth;
    size_t maskedPixels() const;
};
std::vector<std::pair<int, int>> sparseCheckPixels(int width, int height, int pixelCount, uint32_t seed);
SparseCheck runSparseCheck(const TraceScene& trace, const Scene& scene, int lightIndex, int pixelCount,
                           int samples, uint32_t seed);

// The RMSE of layers' V against the check over the pixels both masks hold (as `compare` measures
// by default); NaN when no checked pixel is in both masks.
double estimatedRmse(const SparseCheck& check, const Layers& layers);

}  // namespace ss
