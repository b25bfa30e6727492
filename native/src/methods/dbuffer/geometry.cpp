// How the dbuffer volumes of a scene and light are built and cached.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/dbuffer/geometry.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <list>
#include <mutex>

#include "core/error.h"
#include "core/stopwatch.h"
#include "geometry/mesh_parts.h"
#include "methods/dbuffer/light.h"

namespace ss {

namespace {

bool sameDisk(const Disk& a, const Disk& b) {
    return a.centre == b.centre && a.normal == b.normal && a.radius == b.radius;
}

struct Key {
    Scene::LightGeometryKey geometry;
    Disk disk;
    Bounds fit;
    bool operator==(const Key& o) const {
        return geometry == o.geometry && sameDisk(disk, o.disk) && fit.lo == o.fit.lo && fit.hi == o.fit.hi;
    }
};

constexpr size_t kCacheEntries = 8;
std::mutex cacheMutex;
std::list<std::pair<Key, std::shared_ptr<const DbufferGeometry>>> cache;  // most recent first
std::atomic<size_t> builds{0};

// `earlier`: the last build for this light (may be null); a mesh's volumes depend only on the
// mesh, the disk and the extrusion length, so its part is taken when all three are the same.
std::shared_ptr<const DbufferGeometry> build(const Scene& scene, int lightIndex, const Disk& disk, const Bounds& all,
                                             const DbufferGeometry* earlier, const std::atomic<bool>* cancel) {
    auto g = std::make_shared<DbufferGeometry>();
    g->disk = disk;
    // Far enough that every volume reaches past every receiver: from the light to the far side
    // of the scene, twice over.
    float reach = all.empty() ? 1.0f : glm::length(all.center() - disk.centre) + all.diagonal();
    g->extrusionLength = 2.0f * reach;
    if (earlier && !(sameDisk(earlier->disk, disk) && earlier->extrusionLength == g->extrusionLength)) earlier = nullptr;
    for (size_t i = 0; i < scene.meshes().size(); ++i) {
        const Mesh& mesh = scene.meshes()[i];
        if (!scene.castsFor(int(i), lightIndex) || mesh.triangles.empty()) continue;
        if (cancel && cancel->load(std::memory_order_relaxed))
            fail(SS_ERROR_CANCELLED, "cancelled during dbuffer: silhouettes and volumes");
        DbufferGeometry::MeshPart part{mesh.version, nullptr};
        if (earlier)
            for (const DbufferGeometry::MeshPart& p : earlier->parts)
                if (p.meshVersion == mesh.version) part = p;
        if (part.volumes) {
            ++g->meshesReused;
        } else {
            // Each separate part of the mesh (welded, then its connected pieces) has volumes of
            // its own: the D-buffer pass keeps each part's exit apart (methods/dbuffer/method.cpp).
            auto t0 = Clock::now();
            const std::vector<Mesh> pieces = meshParts(mesh);
            auto volumes = std::make_shared<ShadowVolumes>();
            double extrusionMs = 0.0;
            for (size_t k = 0; k < std::max<size_t>(1, pieces.size()); ++k) {
                const Mesh& piece = pieces.empty() ? mesh : pieces[k];
                DiskSilhouette sil = diskSilhouette(piece, disk);
                auto t1 = Clock::now();
                volumes->append(extrudeVolumes(piece, sil, disk, g->extrusionLength));
                extrusionMs += msSince(t1);
            }
            g->silhouetteMs += msSince(t0) - extrusionMs;  // with the welding and splitting
            g->extrusionMs += extrusionMs;
            part.volumes = std::move(volumes);
            ++g->meshesBuilt;
        }
        g->volumes.append(*part.volumes);
        g->parts.push_back(std::move(part));
    }
    ++builds;
    return g;
}

}  // namespace

std::shared_ptr<const DbufferGeometry> dbufferGeometry(const Scene& scene, int lightIndex, const Bounds& fit,
                                                       const std::atomic<bool>* cancel) {
    Bounds casters;
    for (size_t i = 0; i < scene.meshes().size(); ++i)
        if (scene.castsFor(int(i), lightIndex))
            for (const glm::vec3& p : scene.meshes()[i].positions) casters.extend(p);
    casters.lo = glm::max(casters.lo, fit.lo);
    casters.hi = glm::min(casters.hi, fit.hi);
    Key key{scene.lightGeometryKey(lightIndex), dbufferDisk(scene.light(lightIndex), casters, fit), fit};
    std::shared_ptr<const DbufferGeometry> earlier;  // the newest build for this light, if any
    {
        std::lock_guard<std::mutex> lock(cacheMutex);
        for (auto it = cache.begin(); it != cache.end(); ++it) {
            if (it->first == key) {
                cache.splice(cache.begin(), cache, it);
                return cache.front().second;
            }
            Scene::LightGeometryKey k = it->first.geometry;
            k.geometryVersion = key.geometry.geometryVersion;
            if (!earlier && k == key.geometry) earlier = it->second;
        }
    }
    auto g = build(scene, lightIndex, key.disk, fit, earlier.get(), cancel);
    std::lock_guard<std::mutex> lock(cacheMutex);
    cache.emplace_front(key, g);
    if (cache.size() > kCacheEntries) cache.pop_back();
    return g;
}

size_t dbufferGeometryBuilds() { return builds.load(); }

}  // namespace ss
