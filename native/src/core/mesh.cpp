// How a mesh is validated, its edge adjacency and report are built, and it is placed in the world.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/mesh.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "core/error.h"

namespace ss {

bool Mesh::casts() const { return flags & SS_MESH_CAST; }
bool Mesh::receives() const { return flags & SS_MESH_RECEIVE; }

EdgeAdjacency buildEdgeAdjacency(const std::vector<glm::uvec3>& triangles) {
    EdgeAdjacency adj;
    adj.faceEdges.resize(triangles.size());
    std::unordered_map<uint64_t, uint32_t> index;
    index.reserve(triangles.size() * 2);
    for (uint32_t f = 0; f < triangles.size(); ++f) {
        const glm::uvec3& t = triangles[f];
        for (int k = 0; k < 3; ++k) {
            uint32_t a = t[k], b = t[(k + 1) % 3];
            uint32_t lo = std::min(a, b), hi = std::max(a, b);
            uint64_t key = (uint64_t(lo) << 32) | hi;
            auto [it, inserted] = index.emplace(key, uint32_t(adj.edges.size()));
            if (inserted) {
                Edge e;
                e.v0 = lo;
                e.v1 = hi;
                adj.edges.push_back(std::move(e));
            }
            Edge& e = adj.edges[it->second];
            e.faces.push_back(f);
            e.forward.push_back(a == lo);
            adj.faceEdges[f][k] = it->second;
        }
    }
    return adj;
}

std::vector<glm::vec3> faceNormalsOf(const std::vector<glm::vec3>& p, const std::vector<glm::uvec3>& triangles) {
    std::vector<glm::vec3> normals(triangles.size());
    for (size_t f = 0; f < triangles.size(); ++f) {
        const glm::uvec3& t = triangles[f];
        glm::vec3 n = glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
        float len = glm::length(n);
        bool degenerate = t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || !(len > 0.0f) || !std::isfinite(len);
        normals[f] = degenerate ? glm::vec3(0.0f) : n / len;
    }
    return normals;
}

void Mesh::place(const glm::mat4& transform) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(transform[c][r]))
                fail(SS_ERROR_INVALID_ARGUMENT, "mesh '" + name + "': the transform is not finite");
    // The GPU and the ray tracer place vertices without a perspective divide.
    if (glm::vec4(transform[0][3], transform[1][3], transform[2][3], transform[3][3]) != glm::vec4(0, 0, 0, 1))
        fail(SS_ERROR_INVALID_ARGUMENT, "mesh '" + name + "': the transform is not affine (its last row must be 0 0 0 1)");
    const bool identity = transform == glm::mat4(1.0f);
    std::vector<glm::vec3> world = objectPositions;
    if (!identity)
        for (size_t i = 0; i < world.size(); ++i) {
            world[i] = glm::vec3(transform * glm::vec4(objectPositions[i], 1.0f));
            if (!std::isfinite(world[i].x) || !std::isfinite(world[i].y) || !std::isfinite(world[i].z))
                fail(SS_ERROR_INVALID_ARGUMENT, "mesh '" + name + "': the transform moves vertex " +
                                                    std::to_string(i) + " to a non-finite point");
        }
    const bool mirrors = glm::determinant(glm::mat3(transform)) < 0.0f;
    std::vector<glm::vec3> normals = identity ? objectFaceNormals : faceNormalsOf(world, triangles);
    // The cross product of mirrored edges is the mirrored normal negated: turned back outward.
    if (mirrors)
        for (glm::vec3& n : normals) n = -n;
    if (mirrors != mirrored)
        for (Edge& e : adjacency.edges) e.forward.flip();
    positions = std::move(world);
    faceNormals = std::move(normals);
    objectToWorld = transform;
    mirrored = mirrors;
    report.degenerateFaces = size_t(std::count(faceNormals.begin(), faceNormals.end(), glm::vec3(0.0f)));
}

void Mesh::finalize() {
    for (size_t i = 0; i < objectPositions.size(); ++i) {
        const glm::vec3& p = objectPositions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            std::ostringstream m;
            m << "mesh '" << name << "': vertex " << i << " is not finite (NaN or Inf)";
            fail(SS_ERROR_INVALID_SCENE, m.str());
        }
    }
    for (size_t f = 0; f < triangles.size(); ++f)
        for (int k = 0; k < 3; ++k)
            if (triangles[f][k] >= objectPositions.size()) {
                std::ostringstream m;
                m << "mesh '" << name << "': triangle " << f << " uses vertex index "
                  << triangles[f][k] << " but the mesh has " << objectPositions.size() << " vertices";
                fail(SS_ERROR_INVALID_SCENE, m.str());
            }

    adjacency = buildEdgeAdjacency(triangles);
    mirrored = false;  // the adjacency was just built in the triangles' order
    report = MeshReport{};
    objectFaceNormals = faceNormalsOf(objectPositions, triangles);
    for (const Edge& e : adjacency.edges) {
        if (e.isOpen()) ++report.openEdges;
        else if (e.faces.size() > 2) ++report.nonManifoldEdges;
        else if (!e.isConsistent()) ++report.inconsistentEdges;
    }
    place(objectToWorld);
}

std::string MeshReport::toJson(const std::string& meshName) const {
    std::ostringstream s;
    std::string escaped;
    for (char c : meshName) {
        if (c == '"' || c == '\\') escaped += '\\';
        escaped += c;
    }
    s << "{\"mesh\": \"" << escaped << "\", \"open_edges\": " << openEdges
      << ", \"non_manifold_edges\": " << nonManifoldEdges
      << ", \"inconsistent_edges\": " << inconsistentEdges
      << ", \"degenerate_faces\": " << degenerateFaces
      << ", \"closed_manifold\": " << (closedManifold() ? "true" : "false") << "}";
    return s.str();
}

}  // namespace ss
