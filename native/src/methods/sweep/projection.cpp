// How silhouette edges and fallback triangles are classified, clipped below the sample and
// projected onto the receiver plane.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/projection.h"

#include <cmath>

namespace ss {

namespace {

// Points at or above this fraction of the sample's height would project beyond 1000x their
// distance (or behind the sample): they are clipped away, which keeps the projection finite.
constexpr double kMaxHeightFraction = 0.999;

struct Projector {
    const ReceiverPlane& plane;
    const LightSample& sample;
    double sampleHeight;

    // Where p's shadow falls on the plane, in plane (u, v).
    glm::dvec2 project(const glm::dvec3& p) const {
        double h = plane.height(p);
        glm::dvec3 q;
        if (sample.directional) {
            q = p - sample.toLight * (h / glm::dot(sample.toLight, plane.normal));
        } else {
            q = sample.point + (p - sample.point) * (sampleHeight / (sampleHeight - h));
        }
        return plane.toPlane(q);
    }
    // Positive when the triangle a, b, c faces the sample (counter-clockwise seen from it).
    double facing(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const {
        glm::dvec3 n = glm::cross(b - a, c - a);
        return sample.directional ? glm::dot(n, sample.toLight) : glm::dot(n, sample.point - a);
    }
};

void addEdge(const Projector& pr, const planar::Snap& snap, const glm::dvec3& a, const glm::dvec3& b,
             std::vector<planar::DirectedEdge>* out) {
    glm::dvec2 pa = pr.project(a), pb = pr.project(b);
    snap.addEdge(pa.x, pa.y, pb.x, pb.y, 1, out);
}

// A front face walked backwards (clockwise as seen from the sample, so shadow on the right),
// clipped to the heights the projection can handle.
void addTriangle(const Projector& pr, const planar::Snap& snap, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c,
                 double maxHeight, std::vector<planar::DirectedEdge>* out) {
    glm::dvec3 poly[4];
    int n = 0;
    const glm::dvec3 in[3] = {a, c, b};
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3& p = in[i];
        const glm::dvec3& q = in[(i + 1) % 3];
        double hp = pr.plane.height(p) - maxHeight, hq = pr.plane.height(q) - maxHeight;
        if (hp <= 0) poly[n++] = p;
        if ((hp <= 0) != (hq <= 0)) poly[n++] = p + (q - p) * (hp / (hp - hq));
    }
    for (int i = 0; i < n; ++i) addEdge(pr, snap, poly[i], poly[(i + 1) % n], out);
}

}  // namespace

std::vector<int> sweepOccluders(const Scene& scene, int lightIndex, const ReceiverPlane& plane) {
    std::vector<int> out;
    for (size_t i = 0; i < scene.meshes().size(); ++i)
        if (int(i) != plane.mesh && scene.castsFor(int(i), lightIndex)) out.push_back(int(i));
    return out;
}

bool usesSilhouettes(const Mesh& mesh) { return mesh.report.closedManifold(); }

bool castsOntoPlane(const ReceiverPlane& plane, const LightSample& sample) {
    return sample.directional ? glm::dot(sample.toLight, plane.normal) > 1e-9 : plane.height(sample.point) > 0;
}

void projectMeshSample(const Mesh& m, const ReceiverPlane& plane, const planar::Snap& snap,
                       const LightSample& sample, std::vector<planar::DirectedEdge>* out, ProjectionStats* stats) {
    double sampleHeight = sample.directional ? 1.0 : plane.height(sample.point);
    Projector pr{plane, sample, sampleHeight};
    double maxHeight = sample.directional ? 1e300 : kMaxHeightFraction * sampleHeight;
    auto pos = [&](uint32_t v) { return glm::dvec3(m.positions[v]); };
    bool silhouettes = usesSilhouettes(m);
    if (silhouettes && !sample.directional)
        for (const glm::vec3& p : m.positions)
            if (plane.height(glm::dvec3(p)) >= maxHeight) {
                silhouettes = false;  // the closed outline would cross the clip height
                break;
            }
    std::vector<char> front(m.triangles.size(), 0);
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        const glm::uvec3 t = m.worldTriangle(f);
        front[f] = pr.facing(pos(t[0]), pos(t[1]), pos(t[2])) > 0;
    }
    if (!silhouettes) {
        for (size_t f = 0; f < m.triangles.size(); ++f)
            if (front[f]) {
                const glm::uvec3 t = m.worldTriangle(f);
                addTriangle(pr, snap, pos(t[0]), pos(t[1]), pos(t[2]), maxHeight, out);
                if (stats) ++stats->fallbackTriangles;
            }
        return;
    }
    // Interior edges between two front faces cancel in the sum of projected front faces;
    // what remains are the edges where facing changes, walked as the back face walks them.
    for (const Edge& e : m.adjacency.edges) {
        bool f0 = front[e.faces[0]], f1 = front[e.faces[1]];
        if (f0 == f1) continue;
        bool frontForward = f0 ? e.forward[0] : e.forward[1];
        if (frontForward) addEdge(pr, snap, pos(e.v1), pos(e.v0), out);
        else addEdge(pr, snap, pos(e.v0), pos(e.v1), out);
        if (stats) ++stats->silhouetteEdges;
    }
}

bool projectSample(const Scene& scene, const std::vector<int>& occluders, const ReceiverPlane& plane,
                   const planar::Snap& snap, const LightSample& sample,
                   std::vector<planar::DirectedEdge>* out, ProjectionStats* stats) {
    if (!castsOntoPlane(plane, sample)) return false;
    for (int mi : occluders) projectMeshSample(scene.meshes()[mi], plane, snap, sample, out, stats);
    return true;
}

}  // namespace ss
