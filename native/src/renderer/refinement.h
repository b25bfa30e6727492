// Which pixels of a GL method's result are re-traced with the adaptive reference ("refine=on").
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "core/settings.h"
#include "reference/trace_scene_cache.h"

namespace ss {

// The keys every method accepts for refinement: "refine" (on/off, default off),
// "refine_margin" (pixels around the uncertain ones, 0..32, default 3), "refine_samples" (the
// cap of samples per traced pixel, default 1024) and the adaptive sampling's keys
// (reference/adaptive_sampling.h).
std::vector<std::string> refinementKeys();
bool refinementRequested(const RenderSettings& settings);

// Where the pass is uncertain: inside the mask, 0 < V < 1 or V = 0 beside V = 1 (a hard
// edge), grown by `margin` pixels (within the mask). 1 there, 0 elsewhere.
Image uncertainPixels(const Image& visibility, const Image& mask, int margin);

// Keeps V where the method was certain and traces the uncertain pixels adaptively; V there
// becomes the ray-traced estimate wherever the light reaches the traced surface. Every other
// layer (mask included) stays the method's. With settings.extraLayers adds "rays" (shadow rays
// traced per pixel) and "refined" (1 where the pixels were traced).
void refineUncertainPixels(const Scene& scene, int lightIndex, const RenderSettings& settings,
                           TraceSceneCache& cache, Layers& layers);

}  // namespace ss
