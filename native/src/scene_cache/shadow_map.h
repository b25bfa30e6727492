// The light-centre shadow map every method shares for one light, and the frustum it is fit to
// (shadow_map_fit.cpp; no GL needed for the fit).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/objects.h"

namespace ss {

// The light-centre shadow map shared by every method for one light. Casters only
// (SS_MESH_CAST, and the light's blockers: Scene::castsFor), two-sided. Texel (u, v) = shadow
// clip xy * 0.5 + 0.5 (GL orientation).
struct ShadowMap {
    static constexpr float kEmpty = 1e30f;  // distance stored where no caster is seen
    int size = 0;                           // square, size x size texels
    bool orthographic = false;              // sun
    glm::vec3 origin{0.0f};                 // light centre (sun: a point on the near plane)
    glm::vec3 axis{0.0f, 0.0f, -1.0f};      // view direction of the map (unit)
    glm::mat4 worldToLight{1.0f};           // view matrix (looks down -Z along `axis`)
    glm::mat4 projection{1.0f};             // light view -> clip
    float nearPlane = 0.0f, farPlane = 0.0f;
    float tanHalfFov = 0.0f;  // perspective: tan of the half field of view
    float halfWidth = 0.0f;   // orthographic: half width of the square view in world units
    // False when the scene's bounds could not all fit (light inside the scene, sun looking
    // sideways...): points outside the map are then treated as unshadowed by it.
    bool coversScene = true;
    // R32F: world-space distance from the light centre to the nearest caster (perspective), or
    // distance along `axis` from `origin` (orthographic); kEmpty where no caster is seen.
    gl::Texture distance;
    gl::Texture depth;  // DEPTH_COMPONENT32F window depth of the same draw
    glm::mat4 worldToClip() const { return projection * worldToLight; }
    // World size of one texel at `distanceToLight` (perspective) or anywhere (orthographic).
    float texelWorldSize(float distanceToLight) const;
    // The quantity stored in `distance` for a world point (what a receiver compares with).
    float distanceOf(const glm::vec3& world) const;
};

// The frustum a light's shadow map uses (exposed for tests and CPU methods); no GL needed.
ShadowMap fitShadowMap(const Light& light, const Bounds& bounds, int size);
// How much larger than what can shadow the receivers in view the scene may be and still be
// what the maps fit (shadowFitBounds).
inline constexpr float kSceneFitSlack = 8.0f;
// The box a light's shadow map (and dbuffer's volumes) fit: the scene's bounds, unless they
// reach more than kSceneFitSlack times past the receivers the camera sees (`receivers`, with
// a margin for the light's extent), as one far vertex makes them; then the scene clipped to
// that region, so one outlier never spreads a map over its own extent. No GL needed.
Bounds shadowFitBounds(const Light& light, const Bounds& scene, const Bounds& receivers);

}  // namespace ss
