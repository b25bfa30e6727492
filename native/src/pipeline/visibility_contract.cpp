// How the E_L > 0 test is evaluated on the CPU (the GLSL twin is common/visibility_contract.glsl).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "pipeline/visibility_contract.h"

#include <cmath>

namespace ss {

bool lightReaches(const Light& light, const glm::vec3& P, const glm::vec3& N) {
    if (light.type == LightType::Sun)
        return glm::dot(N, -light.direction()) > -std::sin(light.sunHalfAngle());
    glm::vec3 toLight = light.position() - P;
    if (light.isArea()) {
        if (glm::dot(-toLight, light.direction()) <= 0.0f) return false;
        float nx = glm::dot(N, light.halfAxisX());
        float ny = glm::dot(N, light.halfAxisY());
        bool round = light.type == LightType::Disk || light.type == LightType::Ellipse;
        float reach = round ? std::sqrt(nx * nx + ny * ny) : std::abs(nx) + std::abs(ny);
        return glm::dot(N, toLight) + reach > 0.0f;
    }
    float d = glm::length(toLight);
    if (light.type == LightType::Spot &&
        glm::dot(-toLight, light.direction()) < std::cos(0.5f * light.spotSize) * d)
        return false;
    return glm::dot(N, toLight) + light.radius > 0.0f;
}

}  // namespace ss
