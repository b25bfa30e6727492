// What the penumbra_map method exposes to tests and the benchmark: its light model and its
// CPU geometry stage.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "core/scene.h"
#include "geometry/cones_sheets.h"
#include "pipeline/frame.h"

namespace ss {

// The radius of the sphere penumbra_map puts at the light centre: the sphere radius of a
// point or spot light, the area-equal disk's radius of an area light (Light::equivalentRadius).
float penumbraMapLightRadius(const Light& light);

// The cones and sheets of every casting mesh, silhouettes taken from the map's origin, cone
// bases on its far plane.
ConesSheets buildPenumbraGeometry(const Scene& scene, const ShadowMap& map, float radius,
                                  const ConeSheetSettings& settings);

}  // namespace ss
