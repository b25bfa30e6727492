// How passes draw the scene's GPU meshes: whole, or for a patch only the clusters that reach its
// rectangle, with the see-through meshes one material at a time.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/gl_functions.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "scene_cache/cache_counters.h"
#include "scene_cache/gpu_mesh.h"
#include "scene_cache/moved_region.h"

namespace ss {

// A vertex array with no attributes, for draws that make their vertices from gl_VertexID (a
// full-screen triangle, the see-through meshes, the camera pass's listed triangles).
class EmptyVertexArray {
public:
    void bind();

private:
    gl::VertexArrayHandle vao_;
};

// Whether the box (object space, placed by `m`) may cover a pixel of the region's rectangle; a
// box reaching behind the eye may cover anything.
bool reachesRegion(const PatchRegion& region, const GpuMesh& m, const Bounds& objectBox);
// The region a patch of a width x height pass redraws: nothing without a rectangle (a whole pass).
std::optional<PatchRegion> patchRegion(const std::optional<PixelRect>& rect, const glm::mat4& worldToClip,
                                       int width, int height);
// Confines what follows to `rect` (clears included) when there is one.
void scissorTo(const gl::Functions& g, const std::optional<PixelRect>& rect);

// What a draw of the scene's meshes reads and counts: the scene (which meshes shadow which light,
// Scene::castsFor), its meshes on the GPU, the attribute-less vertex array and the counters
// (patchTriangles: what patches drew).
struct MeshDraws {
    const Scene& scene;
    const std::vector<GpuMesh>& meshes;
    EmptyVertexArray& emptyVertexArray;
    SceneCacheStats& stats;

    // Draws every mesh whose flags contain all of `requiredFlags` with `program` (in use) and the
    // bound framebuffer, setting its placement uniforms; `before` runs for each mesh first (e.g. to
    // set a per-mesh uniform); its face normals go to SSBO binding 0. With a region, only the
    // clusters whose bounds, where their mesh is now, may cover a pixel of its rectangle (a patch
    // after moves: movedBoxes, boxesOnScreen). With `castingFor` a light index, only the meshes
    // that shadow that light. With `skipSeeThrough` set, the see-through meshes are left out.
    void drawWhere(const gl::Program& program, uint32_t requiredFlags,
                   const std::optional<PatchRegion>& region,
                   const std::function<void(const GpuMesh&)>& before, int castingFor,
                   bool skipSeeThrough) const;
    // Draws the see-through meshes that have `requiredFlags` (and, with `castingFor` a light
    // index, shadow that light), whole, one material at a time: unindexed, three vertices per
    // triangle, with a vertex stage that includes "common/see_through_vertex.glsl" and a fragment
    // stage that includes "common/see_through.glsl" (its uniforms set here: setAlphaMaterialUniforms).
    // Placement uniforms and `before` as drawWhere; the mesh's storage as bindMeshStorage.
    void drawSeeThroughWhere(const gl::Program& program, uint32_t requiredFlags,
                             const std::function<void(const GpuMesh&)>& before, int castingFor) const;
};

}  // namespace ss
