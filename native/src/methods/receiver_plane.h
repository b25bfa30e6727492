// What pcss and penumbra_map share on the C++ side: the shadow-ray basis of the receiver-plane
// comparison (shaders/pcss/receiver_plane.glsl).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <glm/glm.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "gl/program.h"
#include "frame/frame.h"

namespace ss {

// uShadowRayBasis of receiver_plane.glsl for `map`.
glm::mat3 shadowRayBasis(const ShadowMap& map);
void setShadowRayBasis(const gl::Program& program, const ShadowMap& map);

// The smallest map quantity (distance, or depth for a sun) of any caster vertex, never below
// the map's near plane; the map's far plane when nothing casts.
float nearestCasterDistance(const Scene& scene, const ShadowMap& map);

}  // namespace ss
