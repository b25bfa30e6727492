// How the reference method fills V, mask, umbra and penumbra over the camera image.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "core/image.h"
#include "core/scene.h"
#include "methods/method.h"
#include "reference/trace_scene_cache.h"

namespace ss {

constexpr int kReferenceDefaultSamples = 256;
// Thresholds of the extra layers (DESIGN.md: umbra V < 0.05, lit V > 0.95).
constexpr float kUmbraBelow = 0.05f;
constexpr float kLitAbove = 0.95f;

// For the surface point seen through each pixel centre: V and mask per the visibility contract;
// with settings.extraLayers also "umbra" (mask and V < 0.05) and "penumbra" (mask and
// 0.05 <= V <= 0.95). Samples per pixel: settings.samples, or 256. Option "threads" (default:
// all cores) only changes speed: every pixel depends on (seed, x, y) alone.
// A null cache builds a throw-away TraceScene.
Layers renderReference(const Scene& scene, int lightIndex, const RenderSettings& settings,
                       TraceSceneCache* cache = nullptr);

}  // namespace ss
