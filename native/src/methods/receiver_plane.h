// What pcss and penumbra_map share on the C++ side: the shadow-ray basis of the receiver-plane
// comparison (shaders/pcss/receiver_plane.glsl) and the camera pass that ends both.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <initializer_list>
#include <utility>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "gl/program.h"
#include "scene_cache/scene_cache.h"

namespace ss {

// uShadowRayBasis of receiver_plane.glsl for `map`.
glm::mat3 shadowRayBasis(const ShadowMap& map);
void setShadowRayBasis(const gl::Program& program, const ShadowMap& map);

// The smallest map quantity (distance, or depth for a sun) of any vertex of a mesh that shadows
// light `lightIndex`, never below the map's near plane; the map's far plane when nothing casts.
float nearestCasterDistance(const Scene& scene, int lightIndex, const ShadowMap& map);

// The camera pass both methods end with: `fragment` drawn full-screen over the shared camera pass
// into the RGBA32F scratch target `target` (cleared to `clear` first), with the shadow map, the
// light and the shadow-ray basis bound; `setInputs` sets the method's own uniforms, binding
// textures from the unit it is given. Returns the target, for readReceiverPlaneLayers.
const gl::Framebuffer& drawReceiverPlanePass(SceneCache& sceneCache, int lightIndex, const ShadowMap& map, const char* target,
                                             const char* fragment, const glm::vec4& clear,
                                             const std::function<void(const gl::Program&, int firstFreeUnit)>& setInputs);
// V (channel 0), mask (1) and, with extraLayers, the `extra` (name, channel) layers in that order.
Layers readReceiverPlaneLayers(const gl::Framebuffer& out, bool extraLayers,
                               std::initializer_list<std::pair<const char*, int>> extra);

}  // namespace ss
