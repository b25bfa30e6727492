// How the umbra and penumbra volumes of a mesh under a disk light are extruded (paper 1, §2.1).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/mesh.h"
#include "geometry/silhouette.h"

namespace ss {

// One vertex of a volume triangle. The three vertices of a triangle carry the same edge and
// extrusion point, so the D-buffer fragment stage can find, exactly and per fragment, the point
// e* of the silhouette edge that the fragment was extruded from (eq. 2's "dist(c, e)"):
// e* is where the line from `extrusion` through the fragment meets the line edgeA-edgeB.
// For a fan triangle edgeA == edgeB (the silhouette vertex itself).
// A silhouette face has no silhouette edge of its own: it carries the line through its vertex
// nearest to the light, parallel to the light plane inside the face's plane (for a box side,
// exactly its top edge): edgeA = that vertex, edgeB = edgeA + the line's direction, and
// `extrusion` holds the face's unit normal instead of an extrusion point (see kind).
enum class VolumeKind : int { Quad = 0, Fan = 1, SilhouetteFace = 2 };
struct VolumeVertex {
    glm::vec3 position{0.0f};
    glm::vec3 edgeA{0.0f};
    glm::vec3 edgeB{0.0f};
    glm::vec3 extrusion{0.0f};
    float kind = 0.0f;  // float(VolumeKind), a vertex attribute
};

// Triangle soups (3 vertices per triangle), world space, no winding guarantees (the D-buffer
// pass draws both sides).
struct ShadowVolumes {
    std::vector<VolumeVertex> umbra;     // trimmed umbra quads + silhouette faces
    std::vector<VolumeVertex> penumbra;  // penumbra quads + fans closing them around the disk
    size_t umbraQuads = 0, penumbraQuads = 0, fanTriangles = 0, silhouetteFaces = 0;
    size_t trimmedCorners = 0;   // umbra corners whose two quads were cut at their intersection
    size_t multiEdgeCorners = 0; // corners (umbra and penumbra) at vertices with 3+ silhouette edges
    size_t openCornerEnds = 0;   // quad ends no partner could be found for (odd counts: open meshes)
    size_t insideDiskEdges = 0;  // edges whose line crosses the disk (open meshes only): see .cpp
    // Per separate part, in soup order: how many umbra and penumbra vertices it has (one entry
    // per extrudeVolumes call; append() keeps the parts apart).
    std::vector<std::pair<size_t, size_t>> parts;
    void append(const ShadowVolumes& other);
};

// The two planes through an edge that touch the disk: the extrusion point of the umbra quad
// (disk and occluder on the same side of its plane) and of the penumbra quad (opposite sides).
struct EdgeExtrusion {
    glm::vec3 pUmbra{0.0f}, pPenumbra{0.0f};
    bool parallel = false;    // the edge is parallel to the light plane (a at infinity)
    bool insideDisk = false;  // the edge's line meets the light plane inside the disk
};
// `inward` points from the edge into the occluder (any length, not along the edge).
EdgeExtrusion edgeExtrusion(const glm::vec3& v1, const glm::vec3& v2, const glm::vec3& inward,
                            const Disk& disk);

// Extrudes one mesh's volumes to `length` beyond each silhouette vertex (choose it so the far
// ends lie beyond every receiver). `fanStepRadians` bounds the angle between two fan triangles.
ShadowVolumes extrudeVolumes(const Mesh& mesh, const DiskSilhouette& silhouette, const Disk& disk,
                             float length, float fanStepRadians = 0.2f);

}  // namespace ss
