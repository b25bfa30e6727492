// Which part of a pixel's camera ray the reference traces: the span between the near and far planes.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cmath>

#include <glm/glm.hpp>

#include "core/camera.h"

namespace ss {

// The part of a pixel's ray between the camera's near and far planes, as GL (and Cycles'
// clip start/end) see it: the contract's pixel centre through Camera::pixelRay.
struct CameraRays {
    const Camera& camera;
    glm::mat4 clipToWorld;
    glm::vec3 eye;

    explicit CameraRays(const Camera& c)
        : camera(c), clipToWorld(glm::inverse(c.worldToClip())), eye(c.position()) {}

    glm::vec3 unproject(glm::vec2 ndc, float z) const {
        glm::vec4 p = clipToWorld * glm::vec4(ndc, z, 1.0f);
        return glm::vec3(p) / p.w;
    }

    // Returns false when the pixel's near/far span is empty or not finite.
    bool span(int x, int y, Ray* ray, float* tNear, float* tFar) const {
        float px = float(x) + 0.5f, py = float(y) + 0.5f;
        *ray = camera.pixelRay(px, py);
        glm::vec2 ndc(2.0f * px / float(camera.width) - 1.0f, 1.0f - 2.0f * py / float(camera.height));
        glm::vec3 a = unproject(ndc, -1.0f), b = unproject(ndc, 1.0f);
        if (camera.isOrthographic()) {
            *tNear = 0.0f;
            *tFar = glm::length(b - a);
        } else {
            *tNear = glm::length(a - eye);
            *tFar = glm::length(b - eye);
        }
        return std::isfinite(*tNear) && std::isfinite(*tFar) && *tFar > *tNear;
    }
};

}  // namespace ss
