// One mesh's triangles in an Embree scene of their own, which the trace scenes instance.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/mesh.h"

namespace ss {

// The process's Embree device: it owns the build threads, and devices are expensive to create.
RTCDevice embreeDevice();
// Throws ss::Error (internal) when Embree recorded an error on the device; `what` says where.
void checkEmbree(RTCDevice device, const char* what);

// A BVH over one mesh, in the coordinates the mesh was given in, so a move (a new transform)
// keeps it and only the instance above it changes. A mesh whose transform cannot be inverted
// (flattened to a plane or a point) is held in world space instead, with the identity above it.
class MeshBvh {
public:
    // What identifies the BVH's content: a BVH with an equal key is the same BVH.
    struct Key {
        uint64_t version = 0;  // Mesh::shapeVersion in object space, Mesh::version in world space
        bool objectSpace = true;
        bool operator==(const Key&) const = default;
        // One number per key (versions are unique over the process), for hash maps.
        uint64_t packed() const { return version * 2u + (objectSpace ? 1u : 0u); }
    };
    static Key keyOf(const Mesh& mesh);
    // The transform that takes the BVH's coordinates to world space.
    static glm::mat4 toWorldOf(const Mesh& mesh);

    explicit MeshBvh(const Mesh& mesh);
    MeshBvh(const MeshBvh&) = delete;
    MeshBvh& operator=(const MeshBvh&) = delete;

    const Key& key() const { return key_; }
    RTCScene scene() const { return scene_.get(); }
    // In the BVH's coordinates: the hit point and normal are rebuilt from them.
    const std::vector<glm::vec3>& positions() const { return positions_; }
    const std::vector<glm::uvec3>& triangles() const { return triangles_; }
    const std::vector<glm::vec3>& faceNormals() const { return faceNormals_; }  // unit, zero if degenerate

private:
    Key key_;
    std::unique_ptr<RTCSceneTy, void (*)(RTCScene)> scene_{nullptr, rtcReleaseScene};
    std::vector<glm::vec3> positions_;
    std::vector<glm::uvec3> triangles_;
    std::vector<glm::vec3> faceNormals_;
};

}  // namespace ss
