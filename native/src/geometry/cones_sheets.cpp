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

// The point where the sheet's plane touches the light's disk (centre c, radius R, normal
// `axis`): the plane through the edge (pa, pb) tangent to the disk on the side opposite the
// outward direction d (unit, perpendicular to axis and to the edge's image). Lines from that
// point through the edge are the outer boundary of the edge's penumbra; the plane meets the far
// plane in the outer common tangent of the two end cones' base circles.
glm::vec3 outerTangentPoint(const PenumbraLight& light, const glm::vec3& pa, const glm::vec3& pb,
                            float za, float zb, const glm::vec3& d) {
    const float R = light.radius;
    // k (a' - c), a' where the edge's line meets the light's plane, k = za - zb: finite when
    // the edge is parallel to that plane (k = 0, a' at infinity).
    const float k = za - zb;
    glm::vec3 h = (pa - light.centre) * k + (pb - pa) * za;
    h -= glm::dot(h, light.axis) * light.axis;
    const float hl = glm::length(h);
    // s = R / |a' - c|: 0 for an edge parallel to the light, 1 when its line grazes the disk.
    const float s = hl > 0.0f ? std::min(R * std::abs(k) / hl, 1.0f) : 0.0f;
    const glm::vec3 toward = hl > 0.0f ? h * (k < 0.0f ? -1.0f / hl : 1.0f / hl) : glm::vec3(0.0f);
    // Tangent points from a' to the circle: c + R s g^ +- R sqrt(1 - s^2) d, with g^ along a'
    // (perpendicular to d: a' lies on the image of the edge's plane through c). The outer one
    // is on the -d side. A line through the disk (s clamped to 1) has no tangent plane: the
    // sheet then passes through the rim point nearest a'.
    return light.centre + R * s * toward - R * std::sqrt(std::max(0.0f, 1.0f - s * s)) * d;
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
}

ConesSheets buildConesSheets(const Mesh& mesh, const PointSilhouette& silhouette,
                             const PenumbraLight& light, const ConeSheetSettings& settings) {
    ConesSheets out;
    const int segments = std::max(3, settings.coneSegments);
    glm::vec3 u, w;
    perpendicularBasis(light.axis, &u, &w);
    auto usable = [&](float z) { return z >= light.nearDepth && z < light.farDepth; };

    // Per silhouette edge, the in-plane direction pointing outward from its image, away from the
    // occluder (zero when there is none): the side its sheet and its share of the cones lie on.
    std::vector<glm::vec3> outward(silhouette.edges.size(), glm::vec3(0.0f));
    for (size_t i = 0; i < silhouette.edges.size(); ++i) {
        const SilhouetteEdge& e = silhouette.edges[i];
        const glm::vec3 pa = mesh.positions[e.a], pb = mesh.positions[e.b];
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
        if (dl > 0.0f) outward[i] = d / dl;
    }
    // Per silhouette edge, where its sheet touches its end cones: the unit normal n of the two
    // base circles' outer common tangent on the outward side (the tangent points are
    // base + C n). With centres B_a, B_b (L apart along e) and radii C_a, C_b,
    // (B_b - B_a).n = C_a - C_b, so n = cos(phi) d + sin(phi) e with sin(phi) = (C_a - C_b) / L.
    // Zero where one circle holds the other (no common tangent).
    std::vector<glm::vec3> touch(silhouette.edges.size(), glm::vec3(0.0f));
    // Vertices whose base circle lies inside the other end's of one of their edges (an edge
    // aimed nearly at the light): that cone adds nothing the bigger one does not cover.
    std::vector<uint8_t> inside(mesh.positions.size(), 0);
    for (size_t i = 0; i < silhouette.edges.size(); ++i) {
        if (outward[i] == glm::vec3(0.0f)) continue;
        const glm::vec3 pa = mesh.positions[silhouette.edges[i].a], pb = mesh.positions[silhouette.edges[i].b];
        const float za = lightDepth(light, pa), zb = lightDepth(light, pb);
        if (!usable(za) || !usable(zb)) continue;
        const glm::vec3 along = onFarPlane(light, pb, zb) - onFarPlane(light, pa, za);
        const float len = glm::length(along);
        if (!(len > 0.0f)) continue;
        const float sinPhi = (coneRadius(light, za) - coneRadius(light, zb)) / len;
        if (!(std::abs(sinPhi) < 1.0f)) {
            inside[sinPhi > 0.0f ? silhouette.edges[i].b : silhouette.edges[i].a] = 1;
            continue;
        }
        touch[i] = std::sqrt(1.0f - sinPhi * sinPhi) * outward[i] + sinPhi * (along / len);
    }

    // Cones: one per silhouette vertex, however many silhouette edges meet there. Where two
    // edges meet, their sheets already cover the outer penumbra on either side and the cone is
    // needed only between the two sheets' tangent points on its base (the corner's own share):
    // it is drawn as that sector, widened by half a segment each side, instead of a whole circle. On a finely
    // tessellated silhouette the edges turn by a few degrees, so a whole cone per vertex drew
    // its penumbra's area once per vertex (most of it over the occluder, discarded): the cost
    // grew with vertices x width^2 instead of length x width.
    out.coneOfVertex.assign(silhouette.vertices.size(), -1);
    out.vertices.reserve(silhouette.vertices.size() * (segments + 1) +
                         silhouette.edges.size() * 4);
    const float step = 2.0f * float(M_PI) / float(segments);
    for (size_t i = 0; i < silhouette.vertices.size(); ++i) {
        const glm::vec3 v = mesh.positions[silhouette.vertices[i].vertex];
        const float zv = lightDepth(light, v);
        if (!usable(zv)) continue;
        const glm::vec3 base = onFarPlane(light, v, zv);
        // The polygon's edges touch the circle (vertices at r / cos(pi / n)), so the cone holds
        // the true cone and the sheet's tangent line meets the polygon: no sliver between them.
        const float radius = coneRadius(light, zv) / std::cos(float(M_PI) / float(segments));
        float from = 0.0f, span = 2.0f * float(M_PI);
        const std::vector<uint32_t>& at = silhouette.vertices[i].edges;
        if (at.size() == 2 && touch[at[0]] != glm::vec3(0.0f) && touch[at[1]] != glm::vec3(0.0f)) {
            // The sector runs from one tangent point to the other the way that avoids the
            // inside, the opposite of the mean of the two edges' outward directions (with very
            // different radii the tangent points tilt so far that this can be the longer way round;
            // on a smooth silhouette they tilt alike and it is the few degrees between them).
            const glm::vec3 mid = outward[at[0]] + outward[at[1]];
            const float kTwoPi = 2.0f * float(M_PI);
            auto angle = [&](const glm::vec3& d) { return std::atan2(glm::dot(d, w), glm::dot(d, u)); };
            auto ccw = [&](float from, float to) { return std::fmod(std::fmod(to - from, kTwoPi) + kTwoPi, kTwoPi); };
            // A hairpin (the edges fold back on each other) keeps the whole cone.
            if (glm::length(mid) > 0.1f) {
                const float a0 = angle(touch[at[0]]), a1 = angle(touch[at[1]]), am = angle(mid);
                float turn = ccw(a0, a1);
                from = a0;
                if (ccw(a0, am + float(M_PI)) < turn) from = a1, turn = kTwoPi - turn;
                if (turn + step < kTwoPi) {
                    from -= 0.5f * step;
                    span = turn + step;
                }
            }
        }
        const bool whole = span >= 2.0f * float(M_PI);
        const int pieces = inside[silhouette.vertices[i].vertex] ? 0 : whole ? segments : std::max(1, int(std::ceil(span / step)));
        out.coneOfVertex[i] = int(out.cones());
        out.coneFirstTriangle.push_back(uint32_t(out.triangles.size()));
        const uint32_t tip = uint32_t(out.vertices.size());
        out.vertices.push_back({v, zv});
        const int rim = pieces == 0 ? 0 : whole ? segments : pieces + 1;
        for (int k = 0; k < rim; ++k) {
            float a = from + span * float(k) / float(pieces);
            out.vertices.push_back({base + radius * (std::cos(a) * u + std::sin(a) * w), zv});
        }
        for (int k = 0; k < pieces; ++k)
            out.triangles.push_back({tip, tip + 1 + k, tip + 1 + (k + 1) % rim});
    }

    // Sheets: one per silhouette edge, on the side away from the occluder.
    out.sheetOfEdge.assign(silhouette.edges.size(), -1);
    for (size_t i = 0; i < silhouette.edges.size(); ++i) {
        const SilhouetteEdge& e = silhouette.edges[i];
        const glm::vec3 pa = mesh.positions[e.a], pb = mesh.positions[e.b];
        const float za = lightDepth(light, pa), zb = lightDepth(light, pb);
        if (!usable(za) || !usable(zb)) continue;
        const glm::vec3 d = outward[i];
        if (d == glm::vec3(0.0f)) continue;
        // The sheet lies in the plane through the edge tangent to the light's disk: its rulings
        // run from the tangent point t through the edge to the far plane, so its far edge is the
        // two base circles' outer common tangent and the quad is planar by construction.
        const glm::vec3 t = outerTangentPoint(light, pa, pb, za, zb, d);
        const glm::vec3 qa = t + (pa - t) * (light.farDepth / za);
        const glm::vec3 qb = t + (pb - t) * (light.farDepth / zb);
        out.sheetOfEdge[i] = int(out.sheets());
        out.sheetFirstTriangle.push_back(uint32_t(out.triangles.size()));
        const uint32_t first = uint32_t(out.vertices.size());
        out.vertices.push_back({pa, za});
        out.vertices.push_back({qa, za});
        out.vertices.push_back({pb, zb});
        out.vertices.push_back({qb, zb});
        out.triangles.push_back({first, first + 2, first + 3});
        out.triangles.push_back({first, first + 3, first + 1});
    }
    return out;
}

}  // namespace ss
