// Which umbra/penumbra volumes the dbuffer method draws for a light, cached while nothing changes.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <atomic>
#include <cstddef>
#include <memory>
#include <vector>

#include "core/scene.h"
#include "geometry/volumes.h"

namespace ss {

struct DbufferGeometry {
    Disk disk;              // the light as the method sees it (methods/dbuffer/light.h)
    ShadowVolumes volumes;  // the volumes of every mesh that shadows the light, concatenated
    float extrusionLength = 0.0f;
    // Each casting mesh's volumes, in `volumes` order, with the Mesh::version they were made
    // from: the next build after a move takes the unchanged meshes' parts.
    struct MeshPart {
        uint64_t meshVersion = 0;
        std::shared_ptr<const ShadowVolumes> volumes;
    };
    std::vector<MeshPart> parts;
    size_t meshesBuilt = 0, meshesReused = 0;  // parts made here, parts taken from an earlier build
    double silhouetteMs = 0.0, extrusionMs = 0.0;  // CPU time of the two stages when built
};

// The volumes of the meshes that shadow light `lightIndex` (Scene::castsFor), built on first use and kept for the same
// (Scene::lightGeometryKey, disk): a mesh edit or move, or this light's edit, rebuilds them; a
// camera edit or another light's keeps them. A few recent entries are kept (thread-safe). A
// rebuild after moves or mesh edits takes the volumes of every mesh whose version is unchanged
// from the last build for the same light, disk and extrusion length (meshesReused).
// Throws ss::Error(SS_ERROR_CANCELLED) between meshes once `cancel` is set.
// `fit`: the box the volumes must reach across and a sun's disk is placed from (the scene's
// bounds, or SceneCache::shadowFitBounds: never a far outlier's extent); part of the key.
std::shared_ptr<const DbufferGeometry> dbufferGeometry(const Scene& scene, int lightIndex, const Bounds& fit,
                                                       const std::atomic<bool>* cancel = nullptr);

// How many times volumes were really built (not found in the cache) since the process started.
size_t dbufferGeometryBuilds();

}  // namespace ss
