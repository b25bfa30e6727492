// How penumbra-map cones (at silhouette vertices) and sheets (along silhouette edges) are built.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/mesh.h"
#include "geometry/silhouette.h"

namespace ss {

// The light as the penumbra map sees it: a sphere (or a disk modelled as one) of radius
// `radius` at `centre`, whose shadow map looks along `axis`. Depth Z is measured along `axis`
// (the shadow map's linear depth), never as Euclidean distance, so the cone radius formula and
// the fragment intensity use the same depth as the shadow map.
struct PenumbraLight {
    glm::vec3 centre{0.0f};
    glm::vec3 axis{0.0f, 0.0f, -1.0f};  // unit
    float radius = 0.0f;                // L_r
    float nearDepth = 0.01f;            // silhouette points closer than this are skipped
    float farDepth = 100.0f;            // Z_far: where the cones' bases lie
};

// One vertex of the cone/sheet geometry: a world position and Z_V, the light depth of the
// silhouette point its ruling starts from (constant over a cone; per-ruling along a sheet).
struct ConeSheetVertex {
    glm::vec3 position;
    float zv;
};

struct ConeSheetSettings {
    int coneSegments = 16;  // triangles per cone
};

struct ConesSheets {
    std::vector<ConeSheetVertex> vertices;
    std::vector<glm::uvec3> triangles;
    // Book-keeping for checks: per silhouette vertex (in PointSilhouette::vertices order) the
    // index of its cone or -1 when skipped (behind the near depth); per silhouette edge the
    // index of its sheet or -1; the triangle ranges of each cone and sheet.
    std::vector<int> coneOfVertex;
    std::vector<int> sheetOfEdge;
    std::vector<uint32_t> coneFirstTriangle, sheetFirstTriangle;
    size_t cones() const { return coneFirstTriangle.size(); }
    size_t sheets() const { return sheetFirstTriangle.size(); }

    void append(const ConesSheets& other);  // concatenates (for several meshes)
};

// C_v = L_r (Z_far − Z_v) / Z_v: the radius of the cone's base on the far plane.
float coneRadius(const PenumbraLight& light, float zv);

// The light depth of a world point.
inline float lightDepth(const PenumbraLight& light, const glm::vec3& p) {
    return glm::dot(p - light.centre, light.axis);
}

// Builds one cone per silhouette vertex and one sheet per silhouette edge of `mesh` (whose
// silhouette from light.centre is `silhouette`). Every sheet is one planar quad (two triangles:
// edge end a, its far corner, edge end b, its far corner as vertices 0..3) on the outer side of
// its edge, away from the occluder: in the plane through the edge tangent to the light's disk
// (the disk of `radius` perpendicular to `axis`), so it touches both end cones. Cone polygons
// are circumscribed about the true cones.
ConesSheets buildConesSheets(const Mesh& mesh, const PointSilhouette& silhouette,
                             const PenumbraLight& light, const ConeSheetSettings& settings = {});

}  // namespace ss
