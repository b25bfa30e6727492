// What a triangle mesh is (object-space vertices, triangles, an object-to-world matrix, and the
// world-space vertices and normals derived from them), and how its edges connect its faces.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/mesh_alpha.h"

namespace ss {

// One undirected edge (v0 < v1) and every face that uses it, in face order.
struct Edge {
    uint32_t v0 = 0, v1 = 0;
    std::vector<uint32_t> faces;
    // For each entry of `faces`: true when that face walks the edge v0 -> v1 in the world
    // winding (Mesh::worldTriangle: reversed under a mirroring placement, set by Mesh::place()).
    std::vector<bool> forward;

    bool isOpen() const { return faces.size() == 1; }
    bool isManifold() const { return faces.size() == 2; }
    // Two faces walking the edge in the same direction disagree on which side is outside.
    bool isConsistent() const { return faces.size() != 2 || forward[0] != forward[1]; }
};

// Edge adjacency of a mesh. Every method that needs silhouettes reads it from here.
struct EdgeAdjacency {
    std::vector<Edge> edges;
    std::vector<glm::uvec3> faceEdges;  // per face: its edges (v0v1, v1v2, v2v0) as indices
};

// What is wrong with a mesh, found once when it enters the scene; methods decide what to do.
struct MeshReport {
    size_t openEdges = 0;
    size_t nonManifoldEdges = 0;       // 3 or more faces
    size_t inconsistentEdges = 0;      // two faces with opposite orientation conventions
    size_t degenerateFaces = 0;        // repeated vertex or zero area
    bool closedManifold() const {
        return openEdges == 0 && nonManifoldEdges == 0 && inconsistentEdges == 0;
    }
    std::string toJson(const std::string& meshName) const;
};

struct Mesh {
    std::string name;
    // The mesh as given: its vertices in object space, its triangles and where it is placed.
    // finalize() derives the shape's and the placement's data below from them; place() moves it.
    std::vector<glm::vec3> objectPositions;
    std::vector<glm::uvec3> triangles;
    glm::mat4 objectToWorld{1.0f};  // affine (last row 0 0 0 1)
    uint32_t flags = 0;  // SS_MESH_CAST | SS_MESH_RECEIVE | SS_MESH_THIN | SS_MESH_CAMERA_HIDDEN
    // What its materials let through on shadow rays; null where it blocks every ray it meets
    // (no materials, or only opaque ones). Shared: copies of a scene do not copy textures.
    std::shared_ptr<const MeshAlpha> alpha;
    // Unique over the process for each content the mesh has had, its placement included (set
    // by the Scene): what is built from world positions is cached by it.
    uint64_t version = 0;
    // Unique for each shape the mesh has had (object-space vertices, triangles, flags; set by the
    // Scene): a move keeps it, so GPU buffers and BVHs keyed by it are kept and drawn with the
    // new matrix.
    uint64_t shapeVersion = 0;

    // Of the shape (finalize()):
    EdgeAdjacency adjacency;
    MeshReport report;
    std::vector<glm::vec3> objectFaceNormals;  // unit, zero for degenerate faces: what the GPU and
                                               // the ray tracer keep across moves
    // Of the placement (finalize() and place()): what the methods read. A mirroring matrix
    // (negative determinant, Blender's negative scale) turns the surface the way Blender does:
    // the same side stays outside, so the world winding is the triangles' order reversed.
    std::vector<glm::vec3> positions;    // objectToWorld applied to objectPositions
    std::vector<glm::vec3> faceNormals;  // of `positions` in the world winding: unit, zero for
                                         // degenerate faces; outward on a closed outward mesh
    bool mirrored = false;               // det(objectToWorld) < 0

    bool casts() const;
    bool receives() const;
    // It has materials that let some light through (see `alpha`).
    bool seeThrough() const { return alpha != nullptr; }
    // objectToWorld is not the identity.
    bool transformed() const { return objectToWorld != glm::mat4(1.0f); }
    // Triangle f as the world sees it: its order, or reversed where the placement mirrors. What
    // tells a face's side from its vertex order reads this, not `triangles`.
    glm::uvec3 worldTriangle(size_t f) const {
        const glm::uvec3& t = triangles[f];
        return mirrored ? glm::uvec3(t[0], t[2], t[1]) : t;
    }

    // Validates (throws ss::Error on NaN/Inf coordinates, out-of-range indices or a bad
    // objectToWorld) and builds the adjacency, the normals, the report and the world positions.
    void finalize();
    // Moves the finalized mesh to `transform` (finite and affine, else ss::Error and the mesh is
    // left as it was): world positions, world normals and the degenerate-face count are made
    // again; the adjacency and the object-space normals stay, but for the edges' `forward` flags,
    // which turn over when the placement starts or stops mirroring.
    void place(const glm::mat4& transform);
};

EdgeAdjacency buildEdgeAdjacency(const std::vector<glm::uvec3>& triangles);
// The unit normal of each triangle, zero for a degenerate one (a repeated vertex, no area).
std::vector<glm::vec3> faceNormalsOf(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles);

}  // namespace ss
