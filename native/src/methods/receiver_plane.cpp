// How pcss and penumbra_map set up their shared shadow-map comparison and class layers.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/receiver_plane.h"

#include <algorithm>

#include "io/metrics.h"

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

Channels splitChannels(const std::vector<glm::vec4>& rgba, int width, int height) {
    Channels out;
    for (Image& img : out.c) img = Image(width, height);
    for (size_t i = 0; i < rgba.size(); ++i)
        for (int k = 0; k < 4; ++k) out.c[k].pixels[i] = rgba[i][k];
    return out;
}

void addClassLayers(Layers& layers, const Image& v, const Image& mask) {
    Image umbra(v.width, v.height, 0.0f), penumbra(v.width, v.height, 0.0f);
    for (size_t i = 0; i < v.pixels.size(); ++i) {
        if (mask.pixels[i] <= 0.5f) continue;
        float x = v.pixels[i];
        umbra.pixels[i] = x < kUmbraThreshold ? 1.0f : 0.0f;
        penumbra.pixels[i] = (x >= kUmbraThreshold && x <= kLitThreshold) ? 1.0f : 0.0f;
    }
    layers.add("umbra", std::move(umbra));
    layers.add("penumbra", std::move(penumbra));
}

}  // namespace ss
