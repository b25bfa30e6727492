// How a mesh is validated and its edge adjacency and report are built.
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

namespace {

void computeFaceNormals(Mesh& mesh) {
    mesh.faceNormals = faceNormalsOf(mesh.positions, mesh.triangles);
    mesh.report.degenerateFaces = size_t(std::count(mesh.faceNormals.begin(), mesh.faceNormals.end(), glm::vec3(0.0f)));
}

}  // namespace

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

std::vector<glm::vec3> objectFaceNormals(const Mesh& mesh) {
    return mesh.objectPositions.empty() ? mesh.faceNormals : faceNormalsOf(mesh.objectPositions, mesh.triangles);
}

void Mesh::setTransform(const glm::mat4& transform) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(transform[c][r]))
                fail(SS_ERROR_INVALID_ARGUMENT, "mesh '" + name + "': the transform is not finite");
    if (objectPositions.empty()) objectPositions = positions;  // as given: identity so far
    std::vector<glm::vec3> moved(objectPositions.size());
    for (size_t i = 0; i < moved.size(); ++i) {
        moved[i] = glm::vec3(transform * glm::vec4(objectPositions[i], 1.0f));
        if (!std::isfinite(moved[i].x) || !std::isfinite(moved[i].y) || !std::isfinite(moved[i].z))
            fail(SS_ERROR_INVALID_ARGUMENT, "mesh '" + name + "': the transform moves vertex " +
                                                std::to_string(i) + " to a non-finite point");
    }
    positions = std::move(moved);
    objectToWorld = transform;
    computeFaceNormals(*this);
}

void Mesh::finalize() {
    for (size_t i = 0; i < positions.size(); ++i) {
        const glm::vec3& p = positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            std::ostringstream m;
            m << "mesh '" << name << "': vertex " << i << " is not finite (NaN or Inf)";
            fail(SS_ERROR_INVALID_SCENE, m.str());
        }
    }
    for (size_t f = 0; f < triangles.size(); ++f)
        for (int k = 0; k < 3; ++k)
            if (triangles[f][k] >= positions.size()) {
                std::ostringstream m;
                m << "mesh '" << name << "': triangle " << f << " uses vertex index "
                  << triangles[f][k] << " but the mesh has " << positions.size() << " vertices";
                fail(SS_ERROR_INVALID_SCENE, m.str());
            }

    adjacency = buildEdgeAdjacency(triangles);
    report = MeshReport{};
    computeFaceNormals(*this);
    for (const Edge& e : adjacency.edges) {
        if (e.isOpen()) ++report.openEdges;
        else if (e.faces.size() > 2) ++report.nonManifoldEdges;
        else if (!e.isConsistent()) ++report.inconsistentEdges;
    }
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
