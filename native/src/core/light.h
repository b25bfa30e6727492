// What a light is: Blender's light shapes in world space, and the geometry every method reads.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "core/light_links.h"

#include "softshadow/softshadow.h"

namespace ss {

enum class LightType { Disk, Ellipse, Square, Rectangle, Point, Spot, Sun };

const char* lightTypeName(LightType type);
bool parseLightType(const std::string& name, LightType* out);

struct Light {
    std::string name;
    LightType type = LightType::Disk;
    glm::mat4 lightToWorld{1.0f};  // Blender's matrix_world; emits along local -Z
    float size = 1.0f;             // area: size (diameter for disk/ellipse)
    float sizeY = 1.0f;            // ellipse/rectangle second size
    float radius = 0.0f;           // point/spot sphere radius
    float angle = 0.0f;            // sun angular diameter, radians
    float spotSize = 0.0f;         // spot full cone angle, radians
    float spotBlend = 0.0f;
    bool castShadows = true;
    // The meshes it lights and those that shadow it (every mesh unless the host linked them);
    // set through Scene::setLightLinks, kept by Scene::updateLight.
    LightLinks links;
    // Unique over the process for each content the light has had (set by the Scene): its
    // shadow maps are cached by it, so editing one light keeps the others' maps.
    uint64_t version = 0;

    bool isArea() const;
    glm::vec3 position() const;   // centre (for sun: unused)
    glm::vec3 direction() const;  // unit emission direction (local -Z in world)
    // World-space half extents of an area light along its local X and Y (object scale applied).
    glm::vec3 halfAxisX() const;
    glm::vec3 halfAxisY() const;
    // One radius for methods that model the light as a disk or sphere: the area-equal disk
    // for area lights, the sphere radius for point/spot, 0 for a sun (see sunHalfAngle()).
    float equivalentRadius() const;
    float sunHalfAngle() const { return 0.5f * angle; }

    // Throws ss::Error naming the light when its values cannot describe a light
    // (non-finite numbers, zero or negative area size, sun angle outside [0, pi)).
    void validate() const;
};

}  // namespace ss
