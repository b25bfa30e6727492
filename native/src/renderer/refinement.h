// Which pixels of a GL method's result are re-traced with the adaptive reference (RenderSettings::refine).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "core/settings.h"
#include "reference/trace_scene.h"
#include "reference/trace_scene_cache.h"

namespace ss {

// The settings every method accepts to tune refinement: "refine_margin", "refine_samples",
// "refine_verify" and the adaptive sampling's (reference/adaptive_sampling.h). Whether to refine,
// and in how many rounds, are render options (RenderSettings::refine, refineRounds).
constexpr int kRefineDefaultVerifyRays = 8;
const SettingTable& refinementSettings();

// Where the pass is uncertain: inside the mask, 0 < V < 1 or V = 0 beside V = 1 (a hard
// edge), grown by `margin` pixels (within the mask). 1 there, 0 elsewhere.
Image uncertainPixels(const Image& visibility, const Image& mask, int margin);

// Checks the pixels where the method was certain with "refine_verify" rays each (a GL pass can
// be certain and wrong: a shadow map's missed caster, a faint penumbra it calls lit), then traces
// adaptively the uncertain pixels and those the check contradicted, with their margin; the guard
// band may follow a penumbra from there. The check covers every pixel, not only the method's
// mask (outside it the method's V is 1: sweep shades its receiver plane only). V of every traced
// pixel becomes the ray-traced estimate wherever the light reaches the surface, and the pixel
// joins the mask; everywhere else V is the method's. Every other layer stays the method's. With settings.extraLayers
// adds "rays" (shadow rays traced per pixel, the check's included) and "refined" (1 where the
// pixels were traced adaptively).
// Returns the pixels traced adaptively (1 there) and the error target their rounds aimed at:
// what the result's estimated RMSE needs (estimatedRmse).
struct Refinement {
    Image traced;
    float errorTarget = 0.0f;
};
// With settings.refineRounds = n > 1 and `landed` set, rounds 1 .. n - 1 land before the last one, each
// handed to `landed` as it lands: the layers as refined up to then (with extraLayers their "rays"
// and "refined" so far), the pixels traced so far and the error target, round of rounds
// (1-based). The uncertain pixels come first, in shares of their adaptive rounds (the largest
// expected change first), so the first round lands without waiting for the check; then the
// check of the certain pixels in bands of rows, the pixels each band contradicts traced in the
// same round. Those rounds aim at a provisional pixel target (the final one needs the whole
// check); the last round is the one-round refinement, bit for bit, and traces only what the
// rounds before it left out (TracedSamples). Without `landed` the rounds change nothing.
struct RefinementRound {
    Layers layers;
    Image traced;
    float errorTarget = 0.0f;
    int round = 0, rounds = 0;
};
using RefinementRoundFn = std::function<void(RefinementRound&)>;
Refinement refineUncertainPixels(const Scene& scene, int lightIndex, const RenderSettings& settings,
                                 TraceSceneCache& cache, Layers& layers, const RefinementRoundFn& landed = {});

}  // namespace ss
