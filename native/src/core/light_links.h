// Which meshes one light lights and which shadow it: Blender's light and shadow linking.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <optional>
#include <vector>

namespace ss {

// Blender 4.0+ resolves a light's receiver collection (light linking) and blocker collection
// (shadow linking) to sets of objects; the host hands the library those sets as mesh indices.
// No set (nullopt) means every mesh, as an empty collection does in Blender. A mesh outside
// `receivers` gets no light from this light (its pixels leave the light's mask, V = 1 there);
// a mesh outside `blockers` casts no shadow of this light (it still shadows other lights).
// The SS_MESH_CAST and SS_MESH_RECEIVE flags still apply on top.
struct LightLinks {
    std::optional<std::vector<int>> receivers;  // sorted, unique mesh indices
    std::optional<std::vector<int>> blockers;   // sorted, unique mesh indices

    bool lights(int mesh) const { return contains(receivers, mesh); }
    bool blockedBy(int mesh) const { return contains(blockers, mesh); }
    bool linked() const { return receivers.has_value() || blockers.has_value(); }
    // Mesh `index` left the scene: it leaves both sets and later meshes move down one index.
    void meshRemoved(int index);
    bool operator==(const LightLinks&) const = default;

private:
    static bool contains(const std::optional<std::vector<int>>& set, int mesh);
};

// Sorts and deduplicates `meshes` and checks each against `meshCount`; throws
// ss::Error(SS_ERROR_INVALID_ARGUMENT) naming `what` ("blocker", "receiver") and the index.
std::vector<int> linkedMeshSet(std::vector<int> meshes, size_t meshCount, const char* what);

}  // namespace ss
