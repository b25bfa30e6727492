// How good a method's image is expected to be: its error against the reference on a sparse set
// of pixels traced exactly (what `auto` picks by and what every result's estimate comes from).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <functional>
#include <string>
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
// for the same seed. Traced with the reference's own sample sequence and seed, adaptively
// (tracePixels with AdaptiveSampling, at most kReferenceDefaultSamples unless `samples` > 0):
// most checked pixels are fully lit or in umbra and are decided by the first 16 rays, which
// makes the check several times cheaper than at a fixed count; where a pixel took every sample it
// equals the reference image of that seed, elsewhere it is within the adaptive error target.
struct SparseCheck {
    std::vector<PixelVisibility> truth;
    size_t maskedPixels() const;
};
std::vector<std::pair<int, int>> sparseCheckPixels(int width, int height, int pixelCount, uint32_t seed);
SparseCheck runSparseCheck(const TraceScene& trace, const Scene& scene, int lightIndex, int pixelCount,
                           int samples, uint32_t seed);

// The RMSE over the check's mask of `leastError` at each checked pixel: what a method whose
// output is constrained is off by at least there (Method::errorLowerBound). 0 for an empty mask.
double checkedLowerBound(const SparseCheck& check,
                         const std::function<double(const PixelVisibility&)>& leastError);

// The RMSE of layers' V against the check over every checked pixel the light reaches (the
// check's mask), whatever the method's own mask: outside it a method's V is 1 by the contract,
// and that is what a composite multiplies there (sweep leaves every surface but its plane at
// 1). As `compare --mask <light>_reference_mask` measures. NaN when the check's mask is empty.
// For a refined result, the checked pixels that were traced again (`traced` non-zero) do not
// count against the check, whose own few rays there are noisier than the refined V; the traced
// pixels' share is the error target their adaptive rounds spread over the mask
// (`tracedRmse`, reached at 0.57–0.83 of it on the bench: the estimate leans high).
double estimatedRmse(const SparseCheck& check, const Layers& layers, const Image* traced = nullptr,
                     double tracedRmse = 0.0);

}  // namespace ss
