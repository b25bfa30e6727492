// How a light's world-space geometry is derived from Blender's light settings.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/light.h"

#include <cmath>

#include "core/error.h"

namespace ss {

const char* lightTypeName(LightType type) {
    switch (type) {
        case LightType::Disk: return "disk";
        case LightType::Ellipse: return "ellipse";
        case LightType::Square: return "square";
        case LightType::Rectangle: return "rectangle";
        case LightType::Point: return "point";
        case LightType::Spot: return "spot";
        case LightType::Sun: return "sun";
    }
    return "unknown";
}

bool parseLightType(const std::string& name, LightType* out) {
    for (LightType t : {LightType::Disk, LightType::Ellipse, LightType::Square, LightType::Rectangle,
                        LightType::Point, LightType::Spot, LightType::Sun})
        if (name == lightTypeName(t)) {
            *out = t;
            return true;
        }
    return false;
}

bool Light::isArea() const {
    return type == LightType::Disk || type == LightType::Ellipse || type == LightType::Square ||
           type == LightType::Rectangle;
}

glm::vec3 Light::position() const { return glm::vec3(lightToWorld[3]); }

glm::vec3 Light::direction() const { return glm::normalize(-glm::vec3(lightToWorld[2])); }

glm::vec3 Light::halfAxisX() const {
    return 0.5f * size * glm::vec3(lightToWorld[0]);
}

glm::vec3 Light::halfAxisY() const {
    float sy = (type == LightType::Ellipse || type == LightType::Rectangle) ? sizeY : size;
    return 0.5f * sy * glm::vec3(lightToWorld[1]);
}

float Light::equivalentRadius() const {
    switch (type) {
        case LightType::Disk:
        case LightType::Ellipse: {
            // Area-equal disk: pi a b = pi r^2.
            return std::sqrt(glm::length(halfAxisX()) * glm::length(halfAxisY()));
        }
        case LightType::Square:
        case LightType::Rectangle: {
            // Area-equal disk: 4 a b = pi r^2.
            float area = 4.0f * glm::length(halfAxisX()) * glm::length(halfAxisY());
            return std::sqrt(area / float(M_PI));
        }
        case LightType::Point:
        case LightType::Spot: return radius;
        case LightType::Sun: return 0.0f;
    }
    return 0.0f;
}

void Light::validate() const {
    auto bad = [&](const std::string& what) {
        fail(SS_ERROR_INVALID_SCENE, "light '" + name + "': " + what);
    };
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(lightToWorld[c][r])) bad("its matrix has a non-finite value");
    for (float v : {size, sizeY, radius, angle, spotSize, spotBlend})
        if (!std::isfinite(v)) bad("a size or angle is not finite");
    if (glm::length(glm::vec3(lightToWorld[2])) <= 0.0f) bad("its matrix has a zero Z axis");
    if (isArea()) {
        bool twoSizes = type == LightType::Ellipse || type == LightType::Rectangle;
        if (!(size > 0.0f) || (twoSizes && !(sizeY > 0.0f)))
            bad("an area light needs a size greater than zero (got " + std::to_string(size) +
                (twoSizes ? " x " + std::to_string(sizeY) : std::string()) + ")");
        if (!(glm::length(halfAxisX()) > 0.0f) || !(glm::length(halfAxisY()) > 0.0f))
            bad("its matrix scales the area to zero");
    }
    if ((type == LightType::Point || type == LightType::Spot) && radius < 0.0f)
        bad("radius must not be negative");
    if (type == LightType::Sun && (angle < 0.0f || angle >= float(M_PI)))
        bad("sun angle must be in [0, pi)");
    if (type == LightType::Spot && !(spotSize > 0.0f && spotSize <= float(M_PI)))
        bad("spot size must be in (0, pi]");
    if (type == LightType::Spot && !(spotBlend >= 0.0f && spotBlend <= 1.0f))
        bad("spot blend must be in [0, 1] (got " + std::to_string(spotBlend) + ")");
}

}  // namespace ss
