// How each Blender light shape is mapped onto the disk light the dbuffer method needs.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/dbuffer/light.h"

#include <cmath>

namespace ss {

Disk dbufferDisk(const Light& light, const Bounds& casters, const Bounds& scene) {
    Disk d;
    switch (light.type) {
        case LightType::Disk:
        case LightType::Ellipse:
        case LightType::Square:
        case LightType::Rectangle:
            d.centre = light.position();
            d.normal = light.direction();
            d.radius = light.equivalentRadius();
            break;
        case LightType::Point:
        case LightType::Spot: {
            d.centre = light.position();
            glm::vec3 to = casters.empty() ? light.direction() : casters.center() - d.centre;
            float l = glm::length(to);
            d.normal = l > 0.0f ? to / l : light.direction();
            d.radius = light.equivalentRadius();
            break;
        }
        case LightType::Sun: {
            float diag = std::max(scene.diagonal(), 1e-3f);
            float distance = 20.0f * diag;
            glm::vec3 centre = scene.empty() ? glm::vec3(0.0f) : scene.center();
            d.normal = light.direction();
            d.centre = centre - distance * d.normal;
            d.radius = distance * std::tan(light.sunHalfAngle());
            break;
        }
    }
    return d;
}

}  // namespace ss
