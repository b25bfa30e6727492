// Which faces of a mesh face a point or a disk light, and which edges are its silhouettes.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/mesh.h"

namespace ss {

// "No face": the missing neighbour of an open edge.
inline constexpr uint32_t kNoFace = 0xffffffffu;

// Rules shared by every silhouette below (documented once here, tested in
// tests/native/test_geometry_silhouette.cpp):
// - Facing is the sign of n·(p − v0) with the face's unit normal n (Mesh::faceNormals) and its
//   first vertex v0; a face is front-facing to p only when it is strictly positive, so a point
//   exactly in the face's plane sees it as back-facing.
// - Degenerate faces (zero normal) take no part: they are never front-facing, never silhouette
//   faces, and an edge is classified only by its non-degenerate faces. An edge whose faces are
//   all degenerate, or that is shared with a degenerate face in a closed mesh (one good face
//   left but the edge is not open in the mesh), is not a silhouette.
// - Open edges (one face in the mesh): always a silhouette (open surfaces occlude from both
//   sides), for the point silhouette and for BOTH the umbra and penumbra silhouettes of a disk.
// - Non-manifold edges (3+ faces): a silhouette when its non-degenerate faces include at least
//   one face of each of the two classes that define that silhouette.
// - Orientation: every silhouette edge is stored as a -> b in the direction walked by its "more
//   front-facing" face (`face`): the front face for a point, the not-none-frontfacing face for an
//   umbra edge, the all-frontfacing face for a penumbra edge. For an open edge whose only face
//   is back-facing (to the point / to the disk centre) the direction is reversed, as if the face
//   were turned towards the light. With this orientation a closed convex mesh's silhouette is
//   one loop whose edges all run the same way around the light direction.

// One silhouette edge.
struct SilhouetteEdge {
    uint32_t edge = 0;            // index into mesh.adjacency.edges
    uint32_t a = 0, b = 0;        // vertex indices, oriented as described above
    uint32_t face = kNoFace;      // the more front-facing face (walks a -> b unless open+flipped)
    uint32_t otherFace = kNoFace; // the face across (first of the other class); kNoFace if open
};

// A silhouette vertex and every silhouette edge that touches it (2 on a simple loop; 3+ where
// loops meet or a non-manifold edge joins: all are kept). Indices point into the same
// std::vector<SilhouetteEdge> the vertices were built from.
struct SilhouetteVertex {
    uint32_t vertex = 0;
    std::vector<uint32_t> edges;
};

// Groups silhouette edges by vertex (sorted by vertex index; edges in input order).
std::vector<SilhouetteVertex> silhouetteVertices(const std::vector<SilhouetteEdge>& edges);

// ---- (a) from a point (the light centre) ----------------------------------------------------

struct PointSilhouette {
    std::vector<uint8_t> frontFacing;      // per face: 1 when strictly front-facing to the point
    std::vector<SilhouetteEdge> edges;     // in mesh.adjacency.edges order
    std::vector<SilhouetteVertex> vertices;
};

// Needs mesh.finalize() to have run (adjacency and faceNormals are read, never rebuilt).
PointSilhouette pointSilhouette(const Mesh& mesh, const glm::vec3& point);

// ---- (b) from a disk light -------------------------------------------------------------------

struct Disk {
    glm::vec3 centre{0.0f};
    glm::vec3 normal{0.0f, 0.0f, -1.0f};  // unit; the side of the disk does not matter here
    float radius = 0.0f;
};

// How a face sees the whole disk.
enum class DiskFacing : uint8_t {
    NoneFront = 0,            // no point of the disk is in the face's positive half-space
    AllFront = 1,             // every point of the disk is
    SilhouetteCentreBack = 2, // a silhouette face: some are, some are not; centre is behind it
    SilhouetteCentreFront = 3 // a silhouette face whose plane has the centre in front
};
inline bool isSilhouetteFace(DiskFacing f) { return f >= DiskFacing::SilhouetteCentreBack; }

// The two extreme disk points of eq. 1 for a face with unit normal n. The paper's printed sign
// does not match its own text; what is kept is its meaning: pNear is the disk point deepest in
// the face's positive half-space (if even it is behind the face, the face is none-frontfacing),
// pFar the one deepest in the negative half-space (if even it is in front, all-frontfacing).
// When n ∥ the disk normal (the face is parallel to the light) every disk point is at the same
// signed distance: pNear = pFar = centre and `parallel` is true.
struct DiskExtremes {
    glm::vec3 pNear{0.0f}, pFar{0.0f};
    bool parallel = false;
};
DiskExtremes diskExtremes(const glm::vec3& faceNormal, const Disk& disk);

// Classifies one face (unit normal, any point of its plane). A degenerate face (zero normal)
// is NoneFront.
DiskFacing classifyFace(const glm::vec3& faceNormal, const glm::vec3& facePoint, const Disk& disk);

struct DiskSilhouette {
    std::vector<DiskFacing> faces;                    // per face
    // Umbra silhouette: edges between a NoneFront face and one that is not NoneFront.
    std::vector<SilhouetteEdge> umbraEdges;
    // Penumbra silhouette: edges between an AllFront face and one that is not AllFront.
    std::vector<SilhouetteEdge> penumbraEdges;
    std::vector<uint32_t> silhouetteFacesCentreBack;  // face indices, ascending
    std::vector<uint32_t> silhouetteFacesCentreFront; // face indices, ascending
    std::vector<SilhouetteVertex> umbraVertices;      // index into umbraEdges
    std::vector<SilhouetteVertex> penumbraVertices;   // index into penumbraEdges
};

// Needs mesh.finalize() to have run. Splits the faces over two threads on large meshes.
DiskSilhouette diskSilhouette(const Mesh& mesh, const Disk& disk);

}  // namespace ss
