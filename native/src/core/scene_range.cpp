// How the scene range is measured from the camera, and what lies beyond it.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/scene_range.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace ss {

namespace {

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

double distanceFrom(const SceneRange& range, const glm::vec3& p) {
    return glm::length(glm::dvec3(p) - range.camera);
}

bool beyond(const SceneRange& range, double distance) { return !(distance <= range.limit); }

}  // namespace

std::string SceneRange::describe() const {
    if (limit >= kMaxWorldCoordinate) return number(limit) + " (the largest distance any scene may span)";
    return number(limit) + " (" + number(kSceneRangeFactor) + " x the camera's view depth " + number(viewDepth) + ")";
}

SceneRange sceneRangeOf(const Camera& camera) {
    SceneRange r;
    const glm::dmat4 view(camera.worldToCamera);
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(camera.projection) * view);
    r.camera = glm::dvec3(glm::inverse(view)[3]);
    for (int k = 0; k < 3; ++k)
        if (!(std::abs(r.camera[k]) <= kMaxWorldCoordinate))
            fail(SS_ERROR_INVALID_SCENE, "the camera is at " + number(r.camera[k]) +
                                             " on one axis, beyond the largest coordinate " +
                                             number(kMaxWorldCoordinate) + ": nothing can be rendered from there");
    // The far plane's corners; an infinite far plane (w = 0) leaves only the absolute bound.
    double depth = 0.0;
    for (int i = 0; i < 4; ++i) {
        glm::dvec4 corner = toWorld * glm::dvec4(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, 1.0, 1.0);
        double d = std::abs(corner.w) > 1e-300 ? glm::length(glm::dvec3(corner) / corner.w - r.camera) : INFINITY;
        depth = std::max(depth, std::isfinite(d) ? d : INFINITY);
    }
    r.viewDepth = depth;
    r.limit = std::min(kSceneRangeFactor * depth, kMaxWorldCoordinate);
    return r;
}

std::optional<std::string> meshOutOfRange(const Mesh& mesh, const SceneRange& range) {
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const double d = distanceFrom(range, mesh.positions[i]);
        if (beyond(range, d))
            return "mesh '" + mesh.name + "' skipped: its vertex " + std::to_string(i) + " is " + number(d) +
                   " from the camera, beyond the scene range " + range.describe();
    }
    return std::nullopt;
}

std::optional<std::string> lightOutOfRange(const Light& light, const SceneRange& range) {
    const double size = std::max({double(light.size), double(light.sizeY), double(light.radius)}) *
                        std::max({glm::length(glm::vec3(light.lightToWorld[0])), glm::length(glm::vec3(light.lightToWorld[1])),
                                  glm::length(glm::vec3(light.lightToWorld[2]))});
    if (beyond(range, size))
        return "light '" + light.name + "' is " + number(size) + " across, beyond the scene range " + range.describe();
    if (light.type == LightType::Sun) return std::nullopt;
    const double d = distanceFrom(range, light.position());
    if (beyond(range, d))
        return "light '" + light.name + "' is " + number(d) + " from the camera, beyond the scene range " +
               range.describe();
    return std::nullopt;
}

}  // namespace ss
