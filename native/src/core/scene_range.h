// Where geometry and lights may be for a render: the one sanity rule (docs/reliability.md,
// "The scene range"), relative to the camera and the depth it sees.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/light.h"
#include "core/mesh.h"

namespace ss {

// How far past the camera's far clip distance geometry and lights may be.
inline constexpr double kSceneRangeFactor = 1e4;
// No coordinate of the camera, and no distance from it, past this (float keeps about 1e8 of
// spacing there; Embree asserts on ray origins past ~1.8e19).
inline constexpr double kMaxWorldCoordinate = 1e15;

struct SceneRange {
    glm::dvec3 camera{0.0};  // the camera's position (orthographic: its view matrix's origin)
    double viewDepth = 0.0;  // the farthest corner of the far clip plane from the camera
    double limit = 0.0;      // the distance from the camera nothing may pass
    std::string describe() const;  // "1e+06 (10000 x the camera's view depth 100)"
};

// Throws ss::Error(SS_ERROR_INVALID_SCENE) for a camera past kMaxWorldCoordinate.
SceneRange sceneRangeOf(const Camera& camera);
// Why the mesh is beyond the range (its first vertex past it, named), or nothing.
std::optional<std::string> meshOutOfRange(const Mesh& mesh, const SceneRange& range);
// Why the light is beyond the range (a sun's position does not count; its size does), or nothing.
std::optional<std::string> lightOutOfRange(const Light& light, const SceneRange& range);

}  // namespace ss
