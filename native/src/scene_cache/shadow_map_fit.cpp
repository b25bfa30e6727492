// Where a light's shadow map looks: the frustum that holds the scene's bounds from the light.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene_cache/shadow_map.h"

namespace ss {

float ShadowMap::texelWorldSize(float distanceToLight) const {
    return orthographic ? 2.0f * halfWidth / float(size)
                        : 2.0f * tanHalfFov * distanceToLight / float(size);
}

float ShadowMap::distanceOf(const glm::vec3& world) const {
    return orthographic ? glm::dot(world - origin, axis) : glm::length(world - origin);
}

namespace {

glm::vec3 upFor(const glm::vec3& axis) {
    return std::abs(axis.z) < 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
}

// Tangent of the half angle a symmetric frustum along `axis` needs to hold every corner, or
// infinity when a corner is not in front of the light.
float tanToHold(const glm::vec3& origin, const glm::vec3& axis, const std::vector<glm::vec3>& pts,
                float eps) {
    glm::mat4 view = glm::lookAt(origin, origin + axis, upFor(axis));
    float t = 0.0f;
    for (const glm::vec3& p : pts) {
        glm::vec3 v = glm::vec3(view * glm::vec4(p, 1.0f));
        float z = -v.z;
        if (z <= eps) return INFINITY;
        t = std::max(t, std::max(std::abs(v.x), std::abs(v.y)) / z);
    }
    return t;
}

// `b` with each half extent `factor` times as long around its centre, plus `pad` on every side.
Bounds grownAround(const Bounds& b, float factor, float pad) {
    const glm::vec3 c = b.center(), half = 0.5f * (b.hi - b.lo) * factor + glm::vec3(pad);
    Bounds g;
    g.extend(c - half);
    g.extend(c + half);
    return g;
}

bool holds(const Bounds& outer, const Bounds& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::lessThanEqual(inner.hi, outer.hi));
}

}  // namespace

Bounds shadowFitBounds(const Light& light, const Bounds& scene, const Bounds& receivers) {
    if (receivers.empty() || scene.empty()) return scene;
    // What can shadow a receiver in view lies between it and the light: within the receivers'
    // box grown by the light's own extent (an area light's rim) and a margin for filter
    // kernels; casters farther out towards the light are drawn depth-clamped onto the near
    // plane, so they still shadow.
    const float margin = 0.25f * receivers.diagonal() + 2.0f * light.equivalentRadius() + 1e-4f;
    const Bounds relevant = grownAround(receivers, 1.0f, margin);
    // The whole scene when it is not much larger than that: such a fit does not follow the
    // camera, so the maps stay valid across camera moves.
    if (holds(grownAround(relevant, kSceneFitSlack, 0.0f), scene)) return scene;
    Bounds clipped;
    clipped.lo = glm::max(scene.lo, relevant.lo);
    clipped.hi = glm::min(scene.hi, relevant.hi);
    return clipped.empty() ? relevant : clipped;
}

ShadowMap fitShadowMap(const Light& light, const Bounds& sceneBounds, int size) {
    ShadowMap m;
    m.size = size;
    Bounds b = sceneBounds;
    if (b.empty()) {
        b.extend(glm::vec3(-1.0f));
        b.extend(glm::vec3(1.0f));
    }
    float diag = std::max(b.diagonal(), 1e-6f);
    std::vector<glm::vec3> pts = b.corners();

    if (light.type == LightType::Sun) {
        m.orthographic = true;
        m.axis = light.direction();
        float radius = 0.5f * diag;
        m.origin = b.center() - m.axis * (radius * 1.05f);
        m.worldToLight = glm::lookAt(m.origin, m.origin + m.axis, upFor(m.axis));
        float hw = 0.0f, far = 0.0f;
        for (const glm::vec3& p : pts) {
            glm::vec3 v = glm::vec3(m.worldToLight * glm::vec4(p, 1.0f));
            hw = std::max(hw, std::max(std::abs(v.x), std::abs(v.y)));
            far = std::max(far, -v.z);
        }
        m.halfWidth = hw * 1.01f + 1e-6f * diag;
        m.nearPlane = 0.0f;
        m.farPlane = far * 1.01f + 1e-6f * diag;
        m.projection = glm::ortho(-m.halfWidth, m.halfWidth, -m.halfWidth, m.halfWidth, m.nearPlane, m.farPlane);
        return m;
    }

    m.origin = light.position();
    float eps = 1e-5f * diag;
    glm::vec3 toCentre = b.center() - m.origin;
    std::vector<glm::vec3> axes;
    if (glm::length(toCentre) > eps) axes.push_back(glm::normalize(toCentre));
    if (light.type != LightType::Point) axes.push_back(light.direction());
    if (axes.empty()) axes.push_back(glm::vec3(0, 0, -1));
    float best = INFINITY;
    m.axis = axes.back();  // the light's own axis when nothing holds the whole scene
    for (const glm::vec3& a : axes) {
        float t = tanToHold(m.origin, a, pts, eps);
        if (t < best) best = t, m.axis = a;
    }
    // Beyond ~80 degrees a single perspective map wastes its texels at the rim; a light inside
    // the scene gets a partial map and says so.
    const float maxTan = std::tan(glm::radians(80.0f));
    m.coversScene = best <= maxTan;
    m.tanHalfFov = std::min(best, maxTan) * 1.01f;
    m.worldToLight = glm::lookAt(m.origin, m.origin + m.axis, upFor(m.axis));
    float nearZ = INFINITY, farZ = 0.0f;
    for (const glm::vec3& p : pts) {
        float z = -(m.worldToLight * glm::vec4(p, 1.0f)).z;
        nearZ = std::min(nearZ, z);
        farZ = std::max(farZ, z);
    }
    m.nearPlane = std::max(nearZ * 0.99f, 1e-4f * diag);
    m.farPlane = std::max(farZ * 1.01f, m.nearPlane * 2.0f);
    m.projection = glm::perspective(2.0f * std::atan(m.tanHalfFov), 1.0f, m.nearPlane, m.farPlane);
    return m;
}

}  // namespace ss
