// How an ss::Scene is turned into Embree scenes: every mesh for camera rays, casters for shadows.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/scene.h"

namespace ss {

class MeshBvh;

// Where a camera ray met the scene. The point is rebuilt from barycentrics (not o + t d) so
// its rounding error is bounded by the triangle's own coordinates.
struct SurfaceHit {
    bool hit = false;
    uint32_t mesh = 0, triangle = 0;
    glm::vec3 point{0.0f};
    glm::vec3 pointError{0.0f};  // conservative absolute error bound of `point` per axis
    glm::vec3 normal{0.0f};      // unit geometric normal, flipped to face the incoming ray
};

// Immutable once built, safe to query from many threads. Holds a reference to nothing in the
// source Scene except what it copies, so the Scene may change afterwards (the cache key, the
// scene id and geometry version, then differs and a new TraceScene is built). It holds meshes
// only: a light or camera edit leaves it valid.
// Two levels: each mesh's BVH (MeshBvh, in its own coordinates) under an instance with its
// transform. A new TraceScene takes over each of `reusable` whose mesh kept its shape, so a
// moved object costs its instance; the camera-ray and shadow-ray scenes share one BVH per mesh.
class TraceScene {
public:
    // `castersOf` a light index: the shadow rays meet only the meshes that shadow that light
    // (Scene::castsFor: its shadow linking); -1: every casting mesh.
    explicit TraceScene(const Scene& scene, const std::vector<std::shared_ptr<const MeshBvh>>& reusable = {},
                        int castersOf = -1);
    ~TraceScene();
    TraceScene(const TraceScene&) = delete;
    TraceScene& operator=(const TraceScene&) = delete;

    uint64_t sceneId() const { return sceneId_; }
    uint64_t geometryVersion() const { return geometryVersion_; }
    // The blocker set its shadow rays see (LightLinks::blockers; nullopt: every casting mesh).
    const std::optional<std::vector<int>>& blockers() const { return blockers_; }
    // Largest absolute coordinate of any vertex: the scale robust offsets are measured against.
    float extent() const { return extent_; }
    // Mesh BVHs this TraceScene built (those it took over do not count).
    int meshBvhBuilds() const { return meshBvhBuilds_; }
    // The BVHs of its meshes, for a later TraceScene to take over.
    std::vector<std::shared_ptr<const MeshBvh>> meshBvhs() const;

    // Nearest surface of any mesh the camera sees along the ray with t in [tNear, tFar]: camera
    // rays pass through a see-through mesh where MeshAlpha::seenByCamera says so (a cut-out's
    // holes), as the GL camera pass's alpha test does.
    SurfaceHit intersect(const Ray& ray, float tNear, float tFar) const;
    // What reaches the end of the segment origin + t dir, t in (0, tFar), through the casting
    // meshes: 0 where an opaque one blocks it, else the product of (1 - alpha) over the
    // see-through surfaces it crosses (1 when it crosses none). The triangle (skipMesh,
    // skipTriangle) is ignored (a flat triangle never shadows its own points).
    float transmission(const glm::vec3& origin, const glm::vec3& dir, float tFar, uint32_t skipMesh,
                       uint32_t skipTriangle) const;
    // The same for n rays sharing one origin (one pixel's light samples), traced as packets of
    // the CPU's width.
    void transmissionMany(const glm::vec3& origin, const glm::vec3* dirs, const float* tFar, size_t n,
                          uint32_t skipMesh, uint32_t skipTriangle, float* transmission) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    uint64_t sceneId_ = 0, geometryVersion_ = 0;
    std::optional<std::vector<int>> blockers_;
    float extent_ = 0.0f;
    int meshBvhBuilds_ = 0;
};

}  // namespace ss
