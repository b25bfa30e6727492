// How pcss and penumbra_map set up their shared shadow-map comparison.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/receiver_plane.h"

#include <algorithm>

namespace ss {

glm::mat3 shadowRayBasis(const ShadowMap& map) {
    // Rows of the view matrix are the map's right, up and backward axes in world space.
    glm::vec3 right(map.worldToLight[0][0], map.worldToLight[1][0], map.worldToLight[2][0]);
    glm::vec3 up(map.worldToLight[0][1], map.worldToLight[1][1], map.worldToLight[2][1]);
    float s = map.orthographic ? map.halfWidth : map.tanHalfFov;
    return glm::mat3(right * s, up * s, map.axis);
}

void setShadowRayBasis(const gl::Program& program, const ShadowMap& map) {
    glm::mat3 b = shadowRayBasis(map);
    // Program::set has no mat3 overload; the glsl mat3 is set through its location.
    GLint loc = program.location("uShadowRayBasis");
    if (loc >= 0) gl::api().ProgramUniformMatrix3fv(program.id(), loc, 1, GL_FALSE, &b[0][0]);
}

float nearestCasterDistance(const Scene& scene, const ShadowMap& map) {
    float best = map.farPlane;
    for (const Mesh& m : scene.meshes()) {
        if (!m.casts()) continue;
        for (const glm::vec3& p : m.positions) {
            float d = map.distanceOf(p);
            if (d > 0.0f) best = std::min(best, d);
        }
    }
    return std::max(best, map.nearPlane);
}

}  // namespace ss
