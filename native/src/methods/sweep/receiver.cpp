// How the receiver plane is found and framed for the sweep method.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/receiver.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace ss {

namespace {

double meshArea(const Mesh& m) {
    double a = 0;
    for (const glm::uvec3& t : m.triangles)
        a += 0.5 * glm::length(glm::cross(glm::dvec3(m.positions[t[1]] - m.positions[t[0]]),
                                          glm::dvec3(m.positions[t[2]] - m.positions[t[0]])));
    return a;
}

// The largest face's unit normal and a point on it; false for a mesh of degenerate faces.
bool referencePlane(const Mesh& m, glm::dvec3* point, glm::dvec3* normal) {
    double best = 0;
    for (const glm::uvec3& t : m.triangles) {
        glm::dvec3 a(m.positions[t[0]]), b(m.positions[t[1]]), c(m.positions[t[2]]);
        glm::dvec3 n = glm::cross(b - a, c - a);
        double l = glm::length(n);
        if (l > best) {
            best = l;
            *point = a;
            *normal = n / l;
        }
    }
    return best > 0;
}

}  // namespace

bool isPlanarMesh(const Mesh& mesh) {
    glm::dvec3 o, n;
    if (!referencePlane(mesh, &o, &n)) return false;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, glm::dvec3(p));
        hi = glm::max(hi, glm::dvec3(p));
    }
    double tol = 1e-5 * std::max(glm::length(hi - lo), 1e-30);
    for (const glm::uvec3& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            if (std::fabs(glm::dot(glm::dvec3(mesh.positions[t[k]]) - o, n)) > tol) return false;
    return true;
}

bool planeOfMesh(const Mesh& mesh, glm::dvec3* point, glm::dvec3* normal) {
    return isPlanarMesh(mesh) && referencePlane(mesh, point, normal);
}

ReceiverPlane findReceiverPlane(const Scene& scene, const Light& light, const std::string& name) {
    const auto& meshes = scene.meshes();
    int chosen = -1;
    if (!name.empty()) {
        for (size_t i = 0; i < meshes.size(); ++i)
            if (meshes[i].name == name) chosen = int(i);
        if (chosen < 0) fail(SS_ERROR_INVALID_ARGUMENT, "sweep: receiver mesh '" + name + "' is not in the scene");
        if (!meshes[chosen].receives())
            fail(SS_ERROR_INVALID_ARGUMENT, "sweep: receiver mesh '" + name + "' does not receive shadows");
        if (!isPlanarMesh(meshes[chosen]))
            fail(SS_ERROR_UNSUPPORTED, "sweep: receiver mesh '" + name + "' is not planar");
    } else {
        double best = 0;
        for (size_t i = 0; i < meshes.size(); ++i) {
            if (!meshes[i].receives() || !light.links.lights(int(i)) || !isPlanarMesh(meshes[i])) continue;
            double a = meshArea(meshes[i]);
            if (a > best) {
                best = a;
                chosen = int(i);
            }
        }
        if (chosen < 0)
            fail(SS_ERROR_UNSUPPORTED, "sweep: the scene has no planar receiving mesh (the method needs a planar receiver)");
    }
    const Mesh& m = meshes[chosen];
    ReceiverPlane r;
    r.mesh = chosen;
    referencePlane(m, &r.origin, &r.normal);
    double side = light.type == LightType::Sun ? glm::dot(r.normal, -glm::dvec3(light.direction()))
                                               : r.height(glm::dvec3(light.position()));
    if (side == 0.0) fail(SS_ERROR_UNSUPPORTED, "sweep: light '" + light.name + "' lies in the receiver plane of '" + m.name + "'");
    if (side < 0) r.normal = -r.normal;
    glm::dvec3 helper = std::fabs(r.normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    r.u = glm::normalize(glm::cross(helper, r.normal));
    r.v = glm::cross(r.normal, r.u);
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::vec3& p : m.positions) {
        glm::dvec2 q = r.toPlane(glm::dvec3(p));
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    r.cu = 0.5 * (lo.x + hi.x);
    r.cv = 0.5 * (lo.y + hi.y);
    double h = 0.5 * std::max(hi.x - lo.x, hi.y - lo.y);
    r.half = h * 1.01 + 1e-12 * std::max(1.0, std::fabs(r.cu) + std::fabs(r.cv));
    return r;
}

}  // namespace ss
