// What the scene camera is, and where a pixel's centre looks (the pixel-alignment contract).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace ss {

// Resolution limits (docs/scene-format.md, "Limits"): a side, the GL_MAX_TEXTURE_SIZE every
// OpenGL 4.5 context has (the camera pass is one texture), and the pixel count that bounds every
// layer (4 bytes a pixel, 256 MiB at most).
inline constexpr int kMaxCameraSide = 16384;
inline constexpr int64_t kMaxCameraPixels = int64_t(8192) * 8192;

struct Ray {
    glm::vec3 origin;
    glm::vec3 direction;  // unit
};

struct Camera {
    glm::mat4 worldToCamera{1.0f};
    glm::mat4 projection{1.0f};  // OpenGL clip space; pixel aspect and shift baked in
    int width = 0, height = 0;
    float pixelAspect = 1.0f;

    bool isOrthographic() const { return projection[3][3] != 0.0f; }
    glm::mat4 worldToClip() const { return projection * worldToCamera; }
    // Pixel (x, y) counts from the top-left; its centre is at (x + 0.5, y + 0.5).
    // NDC: x_ndc = 2 (x + 0.5) / width - 1, y_ndc = 1 - 2 (y + 0.5) / height.
    Ray pixelRay(float px, float py) const;
    // Where a world point lands, in pixel coordinates (x right, y down), continuous.
    glm::vec2 worldToPixel(const glm::vec3& world) const;
    glm::vec3 position() const;
    // Throws ss::Error for non-finite or singular matrices and non-positive resolutions.
    void validate() const;
};

// Builders for hand-written scenes and tests (a Blender-like perspective camera).
Camera makeLookAtCamera(const glm::vec3& from, const glm::vec3& to, const glm::vec3& up,
                        float verticalFovRadians, int width, int height, float nearClip,
                        float farClip);

}  // namespace ss
