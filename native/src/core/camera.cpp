// How pixel centres map to rays and world points map to pixels.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/camera.h"

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace ss {

Ray Camera::pixelRay(float px, float py) const {
    glm::vec2 ndc(2.0f * px / float(width) - 1.0f, 1.0f - 2.0f * py / float(height));
    glm::mat4 inv = glm::inverse(worldToClip());
    glm::vec4 nearP = inv * glm::vec4(ndc, -1.0f, 1.0f);
    glm::vec4 farP = inv * glm::vec4(ndc, 1.0f, 1.0f);
    glm::vec3 a = glm::vec3(nearP) / nearP.w;
    glm::vec3 b = glm::vec3(farP) / farP.w;
    Ray r;
    r.direction = glm::normalize(b - a);
    // Perspective: start at the eye so nothing in front of the near plane is missed.
    r.origin = isOrthographic() ? a : position();
    return r;
}

glm::vec2 Camera::worldToPixel(const glm::vec3& world) const {
    glm::vec4 clip = worldToClip() * glm::vec4(world, 1.0f);
    glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::vec2((ndc.x + 1.0f) * 0.5f * float(width), (1.0f - ndc.y) * 0.5f * float(height));
}

glm::vec3 Camera::position() const { return glm::vec3(glm::inverse(worldToCamera)[3]); }

void Camera::validate() const {
    if (width <= 0 || height <= 0 || width > kMaxCameraSide || height > kMaxCameraSide ||
        int64_t(width) * height > kMaxCameraPixels)
        fail(SS_ERROR_INVALID_SCENE, "camera resolution " + std::to_string(width) + "x" +
                                         std::to_string(height) + " is not usable (width and height 1.." +
                                         std::to_string(kMaxCameraSide) + ", at most " +
                                         std::to_string(kMaxCameraPixels) + " pixels: 8192 x 8192)");
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(worldToCamera[c][r]) || !std::isfinite(projection[c][r]))
                fail(SS_ERROR_INVALID_SCENE, "camera matrix has a non-finite value");
    float det = glm::determinant(worldToClip());
    if (!std::isfinite(det) || std::abs(det) < 1e-30f)
        fail(SS_ERROR_INVALID_SCENE, "camera view-projection matrix is singular");
}

Camera makeLookAtCamera(const glm::vec3& from, const glm::vec3& to, const glm::vec3& up,
                        float verticalFovRadians, int width, int height, float nearClip,
                        float farClip) {
    Camera c;
    c.worldToCamera = glm::lookAt(from, to, up);
    c.projection = glm::perspective(verticalFovRadians, float(width) / float(height), nearClip, farClip);
    c.width = width;
    c.height = height;
    return c;
}

}  // namespace ss
