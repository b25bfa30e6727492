// The cache counters, declared once: SceneCacheStats, Renderer::CacheStats, the C API's
// ss_cache_stat_* and the add-on's native.cache_stats() all come from these lists.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <algorithm>
#include <cstddef>

// X(type, member, name, combine, doc): the C++ member (SceneCacheStats, CacheStats), the C API's name,
// how the renderer adds up its scene caches' values (Sum or Max) and what it counts (the C API's doc).
//
// Counted by each scene cache (SceneCacheStats); the renderer adds up all its scene caches, dropped ones too.
#define SS_SCENE_CACHE_COUNTERS(X)                                                                          \
    X(int, meshUploads, "mesh_uploads", Sum, "meshes uploaded to the GPU (one per mesh shape: a move uploads nothing)") \
    X(int, cameraPasses, "camera_passes", Sum, "camera passes drawn, whole or patched")                  \
    X(int, cameraReadbacks, "camera_readbacks", Sum, "camera passes read back to the CPU (48 MB at 1024x1024)") \
    X(int, shadowMaps, "shadow_maps", Sum, "light shadow maps drawn, whole or patched")                 \
    X(int, shadowMapsEvicted, "shadow_maps_evicted", Sum, "shadow maps dropped to keep the cache within its budget") \
    X(size_t, shadowMapBytesPeak, "shadow_map_bytes_peak", Max, "the most bytes the cached shadow maps of one scene cache held") \
    X(int, cameraPassesPatched, "camera_passes_patched", Sum, "of camera_passes: redrawn only where meshes moved") \
    X(int, shadowMapsPatched, "shadow_maps_patched", Sum, "of shadow_maps: redrawn only where meshes moved") \
    X(size_t, patchTriangles, "patch_triangles", Sum, "triangles those patches (and methods' own patches) drew") \
    X(size_t, cameraPassTriangles, "camera_pass_triangles", Sum, "triangles the camera passes drew (those that may cover a pixel centre)") \
    X(double, uploadMs, "upload_ms", Sum, "milliseconds uploading meshes, until the GL finished")      \
    X(double, cameraPassMs, "camera_pass_ms", Sum, "milliseconds drawing camera passes, until the GL finished") \
    X(double, shadowMapMs, "shadow_map_ms", Sum, "milliseconds drawing shadow maps, until the GL finished")

// Counted by each method object (MethodStats: its work that depends on the light and the geometry
// but not on the camera); the renderer adds up all its methods.
#define SS_METHOD_COUNTERS(X)                                                                         \
    X(int, lightWorkMade, "light_work_made", Sum, "per-light method work made afresh")                \
    X(int, lightWorkKept, "light_work_kept", Sum, "per-light method work taken from an earlier render") \
    X(int, lightWorkPatched, "light_work_patched", Sum, "per-light method work redrawn only where meshes moved")

// Counted by the renderer itself (scene caches made, their ray-tracing scenes, GL method runs).
#define SS_RENDERER_COUNTERS(X)                                                                       \
    X(int, sceneCaches, "frames", Sum, "scene caches made (one per scene)")                                  \
    X(int, traceSceneBuilds, "trace_scene_builds", Sum, "Embree scenes built (one per scene and geometry edit, shared by reference, refinement and auto's check)") \
    X(int, meshBvhBuilds, "mesh_bvh_builds", Sum, "mesh BVHs those scenes built (one per mesh shape: a moved mesh keeps its BVH)") \
    X(double, methodMs, "method_ms", Sum, "milliseconds running GL methods (prepare + render, the shared passes they drew included)")

#define SS_CACHE_COUNTERS(X) SS_SCENE_CACHE_COUNTERS(X) SS_METHOD_COUNTERS(X) SS_RENDERER_COUNTERS(X)

// A struct's members from a list: `struct S { SS_SCENE_CACHE_COUNTERS(SS_COUNTER_MEMBER) };`.
#define SS_COUNTER_MEMBER(type, member, name, combine, doc) type member = 0;

namespace ss {

// What one scene cache drew and uploaded (SS_SCENE_CACHE_COUNTERS says what each counts).
struct SceneCacheStats {
    SS_SCENE_CACHE_COUNTERS(SS_COUNTER_MEMBER)
    size_t shadowMapBytes = 0;  // the cached shadow maps' bytes now (the budget's measure)
};

template <class T>
T combineCounterSum(T total, T value) { return total + value; }
template <class T>
T combineCounterMax(T total, T value) { return std::max(total, value); }
}  // namespace ss
