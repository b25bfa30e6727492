// How penumbra-map cones and sheets are built from a silhouette seen from the light centre.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/cones_sheets.h"

#include <algorithm>
#include <cmath>

namespace ss {
namespace {

// Two unit vectors spanning the plane perpendicular to the (unit) axis.
void perpendicularBasis(const glm::vec3& axis, glm::vec3* u, glm::vec3* w) {
    glm::vec3 helper = std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    *u = glm::normalize(glm::cross(axis, helper));
    *w = glm::cross(axis, *u);
}

// Where the ray from the light centre through p meets the far plane.
glm::vec3 onFarPlane(const PenumbraLight& light, const glm::vec3& p, float zp) {
    return light.centre + (p - light.centre) * (light.farDepth / zp);
}

// The face's vertex that is not on edge (a, b); used to tell the occluder's side of the edge.
bool thirdVertex(const Mesh& mesh, uint32_t face, uint32_t a, uint32_t b, glm::vec3* out) {
    if (face == kNoFace || face >= mesh.triangles.size()) return false;
    const glm::uvec3& t = mesh.triangles[face];
    for (int k = 0; k < 3; ++k)
        if (t[k] != a && t[k] != b) {
            *out = mesh.positions[t[k]];
            return true;
        }
    return false;
}

// Angle between the normals of the quad's two triangles (p0 p1 q1) and (p0 q1 q0).
float quadTwist(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& q1, const glm::vec3& q0) {
    glm::vec3 n1 = glm::cross(p1 - p0, q1 - p0);
    glm::vec3 n2 = glm::cross(q1 - p0, q0 - p0);
    float l1 = glm::length(n1), l2 = glm::length(n2);
    if (!(l1 > 0.0f) || !(l2 > 0.0f)) return 0.0f;
    float c = std::clamp(glm::dot(n1, n2) / (l1 * l2), -1.0f, 1.0f);
    return std::acos(c);
}

}  // namespace

float coneRadius(const PenumbraLight& light, float zv) {
    return light.radius * (light.farDepth - zv) / zv;
}

void ConesSheets::append(const ConesSheets& other) {
    uint32_t vBase = uint32_t(vertices.size());
    uint32_t tBase = uint32_t(triangles.size());
    vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
    for (const glm::uvec3& t : other.triangles) triangles.push_back(t + glm::uvec3(vBase));
    int cBase = int(cones()), sBase = int(sheets());
    for (int c : other.coneOfVertex) coneOfVertex.push_back(c < 0 ? c : c + cBase);
    for (int s : other.sheetOfEdge) sheetOfEdge.push_back(s < 0 ? s : s + sBase);
    for (uint32_t f : other.coneFirstTriangle) coneFirstTriangle.push_back(f + tBase);
    for (uint32_t f : other.sheetFirstTriangle) sheetFirstTriangle.push_back(f + tBase);
    sheetStrips.insert(sheetStrips.end(), other.sheetStrips.begin(), other.sheetStrips.end());
}

ConesSheets buildConesSheets(const Mesh& mesh, const PointSilhouette& silhouette,
                             const PenumbraLight& light, const ConeSheetSettings& settings) {
    ConesSheets out;
    const int segments = std::max(3, settings.coneSegments);
    glm::vec3 u, w;
    perpendicularBasis(light.axis, &u, &w);
    auto usable = [&](float z) { return z >= light.nearDepth && z < light.farDepth; };

    // Cones: one per silhouette vertex, however many silhouette edges meet there.
    out.coneOfVertex.assign(silhouette.vertices.size(), -1);
    out.vertices.reserve(silhouette.vertices.size() * (segments + 1) +
                         silhouette.edges.size() * 4);
    for (size_t i = 0; i < silhouette.vertices.size(); ++i) {
        const glm::vec3 v = mesh.positions[silhouette.vertices[i].vertex];
        const float zv = lightDepth(light, v);
        if (!usable(zv)) continue;
        const glm::vec3 base = onFarPlane(light, v, zv);
        const float radius = coneRadius(light, zv);
        out.coneOfVertex[i] = int(out.cones());
        out.coneFirstTriangle.push_back(uint32_t(out.triangles.size()));
        const uint32_t tip = uint32_t(out.vertices.size());
        out.vertices.push_back({v, zv});
        for (int k = 0; k < segments; ++k) {
            float a = 2.0f * float(M_PI) * float(k) / float(segments);
            out.vertices.push_back({base + radius * (std::cos(a) * u + std::sin(a) * w), zv});
        }
        for (int k = 0; k < segments; ++k)
            out.triangles.push_back({tip, tip + 1 + k, tip + 1 + (k + 1) % segments});
    }

    // Sheets: one per silhouette edge, on the side away from the occluder.
    out.sheetOfEdge.assign(silhouette.edges.size(), -1);
    for (size_t i = 0; i < silhouette.edges.size(); ++i) {
        const SilhouetteEdge& e = silhouette.edges[i];
        const glm::vec3 pa = mesh.positions[e.a], pb = mesh.positions[e.b];
        const float za = lightDepth(light, pa), zb = lightDepth(light, pb);
        if (!usable(za) || !usable(zb)) continue;
        // Normal of the plane through the light centre and the edge, turned away from the
        // adjacent faces (both lie on one side of that plane at a silhouette edge).
        glm::vec3 m = glm::cross(pb - pa, pa - light.centre);
        glm::vec3 inside;
        float side = 0.0f;
        if (thirdVertex(mesh, e.face, e.a, e.b, &inside)) side = glm::dot(m, inside - pa);
        if (side == 0.0f && thirdVertex(mesh, e.otherFace, e.a, e.b, &inside))
            side = glm::dot(m, inside - pa);
        if (side > 0.0f) m = -m;
        // m is perpendicular to the edge's far-plane image, so its in-plane part points
        // straight outward from that image.
        glm::vec3 d = m - glm::dot(m, light.axis) * light.axis;
        float dl = glm::length(d);
        if (!(dl > 0.0f)) continue;
        d /= dl;
        const glm::vec3 qa = onFarPlane(light, pa, za) + coneRadius(light, za) * d;
        const glm::vec3 qb = onFarPlane(light, pb, zb) + coneRadius(light, zb) * d;
        const float twist = quadTwist(pa, pb, qb, qa);
        int strips = int(std::ceil(twist / std::max(settings.maxTwist, 1e-4f)));
        strips = std::clamp(strips, 1, std::max(1, settings.maxSheetStrips));

        out.sheetOfEdge[i] = int(out.sheets());
        out.sheetFirstTriangle.push_back(uint32_t(out.triangles.size()));
        out.sheetStrips.push_back(uint32_t(strips));
        const uint32_t first = uint32_t(out.vertices.size());
        for (int k = 0; k <= strips; ++k) {
            float s = float(k) / float(strips);
            float z = (1.0f - s) * za + s * zb;
            out.vertices.push_back({glm::mix(pa, pb, s), z});
            out.vertices.push_back({glm::mix(qa, qb, s), z});
        }
        for (int k = 0; k < strips; ++k) {
            uint32_t p0 = first + 2 * k, q0 = p0 + 1, p1 = p0 + 2, q1 = p0 + 3;
            out.triangles.push_back({p0, p1, q1});
            out.triangles.push_back({p0, q1, q0});
        }
    }
    return out;
}

}  // namespace ss
