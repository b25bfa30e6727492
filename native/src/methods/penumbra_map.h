// What the penumbra_map method exposes to tests and the benchmark: its light model and its
// CPU geometry stage.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "core/scene.h"
#include "geometry/cones_sheets.h"
#include "methods/method.h"
#include "scene_cache/scene_cache.h"

namespace ss {

// The radius of the sphere penumbra_map puts at the light centre: the sphere radius of a
// point or spot light, the area-equal disk's radius of an area light (Light::equivalentRadius).
float penumbraMapLightRadius(const Light& light);

// How a cone or sheet fragment turns the paper's depth ratio I into a light intensity (setting
// "intensity"): Coverage, the share of the disk seen past a straight edge (0.5 at the hard
// edge, the default), or Paper, the paper's 3I^2 - 2I^3 (0 at the hard edge).
enum class PenumbraIntensity { Coverage = 0, Paper = 1 };
// Throws ss::Error(SS_ERROR_INVALID_ARGUMENT) for a value other than "coverage" or "paper".
PenumbraIntensity intensityRule(const RenderSettings& settings);

// The cones and sheets of every mesh that shadows light `lightIndex` (Scene::castsFor),
// silhouettes taken from the map's origin, cone bases on its far plane.
ConesSheets buildPenumbraGeometry(const Scene& scene, int lightIndex, const ShadowMap& map, float radius,
                                  const ConeSheetSettings& settings);

}  // namespace ss
