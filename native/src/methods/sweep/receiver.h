// Which plane the sweep method casts onto: a named receiving mesh, or the largest planar one,
// with its 2D frame and the box the planar grid covers.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "core/light.h"
#include "core/scene.h"

namespace ss {

struct ReceiverPlane {
    int mesh = -1;          // index into scene.meshes()
    glm::dvec3 origin{0.0};
    glm::dvec3 normal{0.0}; // unit, towards the light
    glm::dvec3 u{0.0}, v{0.0};  // unit, u x v = normal
    double cu = 0, cv = 0;  // centre of the receiver's box in (u, v)
    double half = 1;        // half side of that square box (a little margin added)

    double height(const glm::dvec3& p) const { return glm::dot(p - origin, normal); }
    glm::dvec2 toPlane(const glm::dvec3& p) const { return {glm::dot(p - origin, u), glm::dot(p - origin, v)}; }
    glm::dvec3 toWorld(double pu, double pv) const { return origin + pu * u + pv * v; }
};

// True when every vertex of the mesh lies within a relative 1e-5 of its largest face's plane.
bool isPlanarMesh(const Mesh& mesh);
// A planar mesh's plane: a point on it and its largest face's unit normal; false when the mesh
// is not planar (isPlanarMesh) or all its faces are degenerate.
bool planeOfMesh(const Mesh& mesh, glm::dvec3* point, glm::dvec3* normal);

// `name` empty: the receiving (SS_MESH_RECEIVE) planar mesh of largest area that the light
// lights (its light linking). Throws ss::Error
// naming the problem when the named mesh is missing, not planar or does not receive, when no
// planar receiver exists, or when the light lies in the plane.
ReceiverPlane findReceiverPlane(const Scene& scene, const Light& light, const std::string& name);

}  // namespace ss
