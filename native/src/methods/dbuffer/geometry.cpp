// How the dbuffer volumes of a scene and light are built and cached.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/dbuffer/geometry.h"

#include <atomic>
#include <chrono>
#include <cstring>
#include <list>
#include <mutex>

#include "core/error.h"
#include "core/stopwatch.h"
#include "methods/dbuffer/light.h"

namespace ss {

namespace {

struct Key {
    Scene::LightGeometryKey geometry;
    Disk disk;
    bool operator==(const Key& o) const {
        return geometry == o.geometry && disk.centre == o.disk.centre && disk.normal == o.disk.normal && disk.radius == o.disk.radius;
    }
};

constexpr size_t kCacheEntries = 8;
std::mutex cacheMutex;
std::list<std::pair<Key, std::shared_ptr<const DbufferGeometry>>> cache;  // most recent first
std::atomic<size_t> builds{0};

std::shared_ptr<const DbufferGeometry> build(const Scene& scene, const Disk& disk, const std::atomic<bool>* cancel) {
    auto g = std::make_shared<DbufferGeometry>();
    g->disk = disk;
    Bounds all = scene.bounds();
    // Far enough that every volume reaches past every receiver: from the light to the far side
    // of the scene, twice over.
    float reach = all.empty() ? 1.0f : glm::length(all.center() - disk.centre) + all.diagonal();
    g->extrusionLength = 2.0f * reach;
    for (const Mesh& mesh : scene.meshes()) {
        if (!mesh.casts() || mesh.triangles.empty()) continue;
        if (cancel && cancel->load(std::memory_order_relaxed))
            fail(SS_ERROR_CANCELLED, "cancelled during dbuffer: silhouettes and volumes");
        auto t0 = Clock::now();
        DiskSilhouette sil = diskSilhouette(mesh, disk);
        g->silhouetteMs += msSince(t0);
        auto t1 = Clock::now();
        g->volumes.append(extrudeVolumes(mesh, sil, disk, g->extrusionLength));
        g->extrusionMs += msSince(t1);
    }
    ++builds;
    return g;
}

}  // namespace

std::shared_ptr<const DbufferGeometry> dbufferGeometry(const Scene& scene, int lightIndex,
                                                       const std::atomic<bool>* cancel) {
    Bounds casters;
    for (const Mesh& m : scene.meshes())
        if (m.casts())
            for (const glm::vec3& p : m.positions) casters.extend(p);
    Key key{scene.lightGeometryKey(lightIndex),
            dbufferDisk(scene.light(lightIndex), casters, scene.bounds())};
    {
        std::lock_guard<std::mutex> lock(cacheMutex);
        for (auto it = cache.begin(); it != cache.end(); ++it)
            if (it->first == key) {
                cache.splice(cache.begin(), cache, it);
                return cache.front().second;
            }
    }
    auto g = build(scene, key.disk, cancel);
    std::lock_guard<std::mutex> lock(cacheMutex);
    cache.emplace_front(key, g);
    if (cache.size() > kCacheEntries) cache.pop_back();
    return g;
}

size_t dbufferGeometryBuilds() { return builds.load(); }

}  // namespace ss
