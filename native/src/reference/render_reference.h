// How the reference method fills V and mask over the camera image.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "core/settings.h"
#include "reference/trace_scene_cache.h"

namespace ss {

constexpr int kReferenceDefaultSamples = 256;
// With "adaptive=on" the sample count is a cap per pixel, most pixels stop far below it.
constexpr int kReferenceAdaptiveDefaultSamples = 1024;

// Every setting renderReference reads.
const SettingTable& referenceSettings();

// For the surface point seen through each pixel centre: V and mask per the visibility contract
// (the renderer adds the class layers, core/visibility_classes.h). Samples per pixel: settings.samples, or 256. Option "threads" (default:
// all cores) only changes speed: every pixel depends on (seed, x, y) alone.
// Option "adaptive" (default off) samples in rounds (reference/adaptive_sampling.h) and, with
// settings.extraLayers, adds the layer "rays": shadow rays traced per pixel.
// A null cache builds a throw-away TraceScene.
Layers renderReference(const Scene& scene, int lightIndex, const RenderSettings& settings,
                       TraceSceneCache* cache = nullptr);

}  // namespace ss
