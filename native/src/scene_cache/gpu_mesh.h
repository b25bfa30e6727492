// The scene's meshes on the GPU: each mesh's buffers, placement and clusters, uploaded once per
// shape (a move only places the mesh again).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/gl_functions.h"
#include "gl/objects.h"
#include "scene_cache/cache_counters.h"
#include "scene_cache/see_through.h"

namespace ss {

// One scene mesh on the GPU, in its object space (the coordinates as given) with its matrix: a
// moved mesh keeps its buffers. Vertex attribute 0 = object position (vec3); indexed triangles.
// Vertex shaders take world = uObjectToWorld * position where uTransformed is 1 and the position
// itself where it is 0 (so meshes without a transform draw exactly their world coordinates);
// face normals go to world space with mat3(uNormalToWorld) (see "common/mesh.vert.glsl").
struct GpuMesh {
    int meshIndex = 0;          // into scene.meshes()
    uint64_t shapeVersion = 0;  // the Mesh::shapeVersion these buffers hold
    uint32_t flags = 0;
    GLsizei indexCount = 0;
    bool transformed = false;       // objectToWorld is not the identity
    glm::mat4 objectToWorld{1.0f};  // the mesh's current placement
    glm::mat4 normalToWorld{1.0f};  // inverse transpose of its 3x3 part
    gl::VertexArrayHandle vao;
    gl::BufferHandle positions;    // vec3 per vertex, object space
    gl::BufferHandle indices;      // uint32 x3 per triangle
    gl::BufferHandle faceNormals;  // SSBO, vec4 per triangle (xyz unit in object space, 0 for degenerate)
    // Runs of consecutive triangles (kClusterTriangles each, the last fewer) with their bounds in
    // object space: a patch of a pass draws only the runs that reach its rectangle, so a small
    // object moved beside a large mesh does not redraw all of it (the camera pass, whole or
    // patched, tests the triangles of those runs only).
    struct Cluster {
        uint32_t firstTriangle = 0, triangleCount = 0;
        Bounds bounds;
    };
    static constexpr uint32_t kClusterTriangles = 1024;
    std::vector<Cluster> clusters;
    // Its materials where the mesh lets light through (Mesh::alpha), else null.
    std::shared_ptr<const GpuSeeThrough> seeThrough;
    bool casts() const;
    bool receives() const;
};

// Binds what a vertex stage that fetches its own vertices reads of mesh `m`: face normals (SSBO 0),
// indices (2), object positions (3) and, for a see-through mesh, its corner UVs (4) and triangle
// materials (5) ("common/see_through_vertex.glsl", "camera/gbuffer.vert.glsl").
void bindMeshStorage(const gl::Functions& g, const GpuMesh& m);

// The scene's meshes on the GPU, in scene order, kept across edits.
class GpuMeshes {
public:
    // The meshes as `scene` is now; when its geometry version changed since the last call,
    // uploads the shapes not held yet (a mesh's buffers are kept by its shape version) and places
    // every mesh where it is now. Needs the GL context current.
    const std::vector<GpuMesh>& update(const Scene& scene, SceneCacheStats& stats);

private:
    std::vector<GpuMesh> meshes_;
    uint64_t geometryVersion_ = 0;  // 0: never uploaded
};

}  // namespace ss
