// How the point and disk silhouettes of a mesh are found (rules in silhouette.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/silhouette.h"

#include <algorithm>

#include "core/split_two.h"

namespace ss {

namespace {

bool degenerate(const glm::vec3& n) { return n.x == 0.0f && n.y == 0.0f && n.z == 0.0f; }

// Builds an oriented silhouette edge. `front` is the face of the "more front" class (kNoFace
// when the edge's faces hold none, only possible for an open edge), `back` the other.
SilhouetteEdge orient(const Mesh& mesh, uint32_t edgeIndex, uint32_t front, uint32_t back,
                      bool flip) {
    const Edge& e = mesh.adjacency.edges[edgeIndex];
    SilhouetteEdge s;
    s.edge = edgeIndex;
    s.face = front;
    s.otherFace = back;
    bool forward = true;
    for (size_t k = 0; k < e.faces.size(); ++k)
        if (e.faces[k] == front) forward = e.forward[k];
    if (flip) forward = !forward;
    s.a = forward ? e.v0 : e.v1;
    s.b = forward ? e.v1 : e.v0;
    return s;
}

// Classifies edges by a per-face predicate `upper(face)` (the "more front" class) and appends
// the silhouette edges. Degenerate faces are skipped (see silhouette.h).
template <class Upper>
void collectEdges(const Mesh& mesh, Upper upper, std::vector<SilhouetteEdge>& out) {
    const auto& edges = mesh.adjacency.edges;
    for (uint32_t i = 0; i < edges.size(); ++i) {
        const Edge& e = edges[i];
        if (e.isOpen()) {
            uint32_t f = e.faces[0];
            if (degenerate(mesh.faceNormals[f])) continue;
            bool up = upper(f);
            out.push_back(orient(mesh, i, f, kNoFace, !up));
            continue;
        }
        uint32_t firstUp = kNoFace, firstDown = kNoFace;
        for (uint32_t f : e.faces) {
            if (degenerate(mesh.faceNormals[f])) continue;
            if (upper(f)) {
                if (firstUp == kNoFace) firstUp = f;
            } else if (firstDown == kNoFace) {
                firstDown = f;
            }
        }
        if (firstUp != kNoFace && firstDown != kNoFace)
            out.push_back(orient(mesh, i, firstUp, firstDown, false));
    }
}

}  // namespace

std::vector<SilhouetteVertex> silhouetteVertices(const std::vector<SilhouetteEdge>& edges) {
    std::vector<std::pair<uint32_t, uint32_t>> ends;  // (vertex, edge)
    ends.reserve(edges.size() * 2);
    for (uint32_t i = 0; i < edges.size(); ++i) {
        ends.emplace_back(edges[i].a, i);
        ends.emplace_back(edges[i].b, i);
    }
    std::sort(ends.begin(), ends.end());
    std::vector<SilhouetteVertex> out;
    for (const auto& [v, e] : ends) {
        if (out.empty() || out.back().vertex != v) out.push_back(SilhouetteVertex{v, {}});
        out.back().edges.push_back(e);
    }
    return out;
}

PointSilhouette pointSilhouette(const Mesh& mesh, const glm::vec3& point) {
    PointSilhouette s;
    size_t n = mesh.triangles.size();
    s.frontFacing.assign(n, 0);
    splitTwo(n, [&](size_t begin, size_t end) {
        for (size_t f = begin; f < end; ++f) {
            const glm::vec3& nf = mesh.faceNormals[f];
            glm::vec3 v0 = mesh.positions[mesh.triangles[f][0]];
            s.frontFacing[f] = glm::dot(nf, point - v0) > 0.0f ? 1 : 0;
        }
    });
    collectEdges(mesh, [&](uint32_t f) { return s.frontFacing[f] != 0; }, s.edges);
    s.vertices = silhouetteVertices(s.edges);
    return s;
}

DiskExtremes diskExtremes(const glm::vec3& faceNormal, const Disk& disk) {
    DiskExtremes x;
    // The in-plane part of n: moving along it raises the signed distance to the face fastest.
    glm::vec3 inPlane = faceNormal - glm::dot(faceNormal, disk.normal) * disk.normal;
    float len = glm::length(inPlane);
    // Below ~1e-6 the direction is noise and r·|inPlane| is far below float resolution of the
    // signed distance anyway: treat the face as parallel to the light.
    if (!(len > 1e-6f)) {
        x.pNear = x.pFar = disk.centre;
        x.parallel = true;
        return x;
    }
    glm::vec3 d = inPlane / len;
    x.pNear = disk.centre + disk.radius * d;
    x.pFar = disk.centre - disk.radius * d;
    return x;
}

DiskFacing classifyFace(const glm::vec3& faceNormal, const glm::vec3& facePoint, const Disk& disk) {
    if (degenerate(faceNormal)) return DiskFacing::NoneFront;
    DiskExtremes x = diskExtremes(faceNormal, disk);
    if (!(glm::dot(faceNormal, x.pNear - facePoint) > 0.0f)) return DiskFacing::NoneFront;
    if (glm::dot(faceNormal, x.pFar - facePoint) > 0.0f) return DiskFacing::AllFront;
    return glm::dot(faceNormal, disk.centre - facePoint) > 0.0f ? DiskFacing::SilhouetteCentreFront
                                                                : DiskFacing::SilhouetteCentreBack;
}

DiskSilhouette diskSilhouette(const Mesh& mesh, const Disk& disk) {
    DiskSilhouette s;
    size_t n = mesh.triangles.size();
    s.faces.assign(n, DiskFacing::NoneFront);
    splitTwo(n, [&](size_t begin, size_t end) {
        for (size_t f = begin; f < end; ++f)
            s.faces[f] = classifyFace(mesh.faceNormals[f], mesh.positions[mesh.triangles[f][0]], disk);
    });
    for (uint32_t f = 0; f < n; ++f) {
        if (s.faces[f] == DiskFacing::SilhouetteCentreBack) s.silhouetteFacesCentreBack.push_back(f);
        if (s.faces[f] == DiskFacing::SilhouetteCentreFront) s.silhouetteFacesCentreFront.push_back(f);
    }
    collectEdges(mesh, [&](uint32_t f) { return s.faces[f] != DiskFacing::NoneFront; }, s.umbraEdges);
    collectEdges(mesh, [&](uint32_t f) { return s.faces[f] == DiskFacing::AllFront; }, s.penumbraEdges);
    // An open edge's face may be NoneFront (umbra rule flips it) or AllFront; for the open-edge
    // orientation of the penumbra silhouette the "turned towards the light" direction must be
    // the same as for the umbra one, so re-orient open penumbra edges by the centre's side.
    for (std::vector<SilhouetteEdge>* edges : {&s.penumbraEdges, &s.umbraEdges})
        for (SilhouetteEdge& e : *edges) {
            if (e.otherFace != kNoFace) continue;
            uint32_t f = e.face;
            const glm::vec3& nf = mesh.faceNormals[f];
            bool centreFront = glm::dot(nf, disk.centre - mesh.positions[mesh.triangles[f][0]]) > 0.0f;
            e = orient(mesh, e.edge, f, kNoFace, !centreFront);
        }
    s.umbraVertices = silhouetteVertices(s.umbraEdges);
    s.penumbraVertices = silhouetteVertices(s.penumbraEdges);
    return s;
}

}  // namespace ss
