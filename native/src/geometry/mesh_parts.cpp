// How a mesh is welded and split into its connected parts for the disk silhouettes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/mesh_parts.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <unordered_map>

namespace ss {

namespace {

struct PositionHash {
    size_t operator()(const glm::vec3& p) const {
        uint32_t b[3];
        std::memcpy(b, &p, sizeof b);
        return size_t(b[0]) * 73856093u ^ size_t(b[1]) * 19349663u ^ size_t(b[2]) * 83492791u;
    }
};

Mesh finalized(const Mesh& from, std::vector<glm::vec3> positions, std::vector<glm::uvec3> triangles) {
    Mesh m;
    m.name = from.name;
    m.flags = from.flags;
    m.objectPositions = std::move(positions);  // world positions: the part's matrix is the identity
    m.triangles = std::move(triangles);
    m.finalize();
    return m;
}

uint32_t root(std::vector<uint32_t>& parent, uint32_t f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
}

}  // namespace

std::vector<Mesh> meshParts(const Mesh& mesh, size_t maxParts) {
    const Mesh* source = &mesh;
    Mesh welded;
    if (mesh.report.openEdges > 0) {
        std::unordered_map<glm::vec3, uint32_t, PositionHash> ids;
        std::vector<uint32_t> remap(mesh.positions.size());
        std::vector<glm::vec3> positions;
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            auto [it, added] = ids.emplace(mesh.positions[i], uint32_t(positions.size()));
            if (added) positions.push_back(mesh.positions[i]);
            remap[i] = it->second;
        }
        if (positions.size() < mesh.positions.size()) {
            std::vector<glm::uvec3> triangles;
            triangles.reserve(mesh.triangles.size());
            for (size_t f = 0; f < mesh.triangles.size(); ++f) {
                const glm::uvec3 t = mesh.worldTriangle(f);
                triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
            }
            welded = finalized(mesh, std::move(positions), std::move(triangles));
            source = &welded;
        }
    }
    // Connected pieces: faces joined through the edges they share.
    const size_t faces = source->triangles.size();
    std::vector<uint32_t> parent(faces);
    std::iota(parent.begin(), parent.end(), 0u);
    for (const Edge& e : source->adjacency.edges)
        for (size_t k = 1; k < e.faces.size(); ++k) {
            uint32_t a = root(parent, e.faces[0]), b = root(parent, e.faces[k]);
            if (a != b) parent[b] = a;
        }
    std::unordered_map<uint32_t, uint32_t> pieceOf;
    std::vector<uint32_t> piece(faces);
    for (uint32_t f = 0; f < faces; ++f) {
        auto [it, added] = pieceOf.emplace(root(parent, f), uint32_t(pieceOf.size()));
        piece[f] = it->second;
    }
    std::vector<Mesh> parts;
    if (pieceOf.size() <= 1 || pieceOf.size() > maxParts) {
        if (source == &welded) parts.push_back(std::move(welded));
        return parts;
    }
    std::vector<std::vector<glm::uvec3>> triangles(pieceOf.size());
    std::vector<std::vector<glm::vec3>> positions(pieceOf.size());
    std::vector<uint32_t> local(source->positions.size(), UINT32_MAX),
        localPiece(source->positions.size(), UINT32_MAX);
    // Piece by piece, so a vertex two pieces share (they touch at a point) gets one copy in each.
    std::vector<uint32_t> order(faces);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return piece[a] < piece[b]; });
    for (uint32_t f : order) {
        const uint32_t p = piece[f];
        glm::uvec3 t;
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = source->worldTriangle(f)[k];
            if (localPiece[v] != p) {
                localPiece[v] = p;
                local[v] = uint32_t(positions[p].size());
                positions[p].push_back(source->positions[v]);
            }
            t[k] = local[v];
        }
        triangles[p].push_back(t);
    }
    parts.reserve(pieceOf.size());
    for (size_t p = 0; p < pieceOf.size(); ++p)
        parts.push_back(finalized(mesh, std::move(positions[p]), std::move(triangles[p])));
    return parts;
}

}  // namespace ss
