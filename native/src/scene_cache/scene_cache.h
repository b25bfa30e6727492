// One scene's GPU and geometry cache, kept by the renderer across renders, edits and animation
// frames: the meshes on the GPU, the camera G-buffer, one light-centre shadow map per light and
// the Embree scenes, each made once and kept while what it depends on is unchanged (per-mesh,
// per-light, camera and geometry versions of the Scene). docs/cache.md says what each keeps.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/scene.h"
#include "gl/gl_functions.h"
#include "gl/program.h"
#include "reference/trace_scene_cache.h"
#include "scene_cache/cache_counters.h"
#include "scene_cache/camera_pass.h"
#include "scene_cache/gpu_mesh.h"
#include "scene_cache/mesh_draws.h"
#include "scene_cache/moved_region.h"
#include "scene_cache/shadow_map.h"
#include "scene_cache/shadow_map_cache.h"

namespace ss {

class SceneCache {
public:
    static constexpr int kDefaultShadowMapSize = 2048;
    // What the cached shadow maps may hold between renders: eight 2048² maps (distance +
    // depth, 32 MiB each). One render may add its own maps on top until the next trim.
    static constexpr size_t kDefaultShadowMapBudget = size_t(256) << 20;

    explicit SceneCache(const Scene& scene);
    ~SceneCache();
    SceneCache(const SceneCache&) = delete;
    SceneCache& operator=(const SceneCache&) = delete;

    const Scene& scene() const { return *scene_; }
    const Camera& camera() const { return scene_->camera(); }
    void setCameraCulling(CameraCulling culling) { camera_.setCulling(culling); }
    // The same scene (same id) after edits: passes whose inputs changed are redrawn on their
    // next use, the rest are kept (a mesh's buffers by its version, a shadow map by its light's
    // version and the geometry version, the camera pass by the camera and geometry versions).
    void setScene(const Scene& scene) { scene_ = &scene; }
    const Light& light(int index) const;  // throws ss::Error(SS_ERROR_INVALID_ARGUMENT)
    // The GL function table; throws ss::Error(SS_ERROR_GL) when called off the render thread
    // (CPU methods run on the caller's thread and have no GL).
    const gl::Functions& gl() const;

    // ---- shared passes (GL methods only; each drawn once and kept while its inputs are) ----
    const std::vector<GpuMesh>& meshes();
    const CameraPass& cameraPass();
    const CameraImages& cameraImages();  // read back on first call
    // The world bounds of the receiving surfaces the camera pass sees (read back a band of
    // rows at a time; empty when none), kept with the camera pass.
    const Bounds& receiversInView();
    // shadowFitBounds for light `lightIndex` with the scene and receiversInView().
    Bounds shadowFitBounds(int lightIndex);
    // size 0 = kDefaultShadowMapSize; one map per (light, size), kept until trimCache() evicts
    // it. The reference stays valid until the next trimCache().
    const ShadowMap& shadowMap(int lightIndex, int size = 0);
    // Drops the least recently used shadow maps until the rest fit in `budgetBytes`. Called
    // between renders (never during one, so the maps a render holds stay alive). Reads no scene:
    // the renderer trims the caches of other scenes too.
    void trimCache(size_t budgetBytes);
    // Drops the passes whose inputs changed and the maps of lights edited or removed since. Needs
    // the scene: only after setScene() with the scene as it is now.
    void dropStale();
    size_t shadowMapBytes() const { return stats_.shadowMapBytes; }
    // Drops the CPU copy of the camera pass (cameraImages(), 48 bytes a pixel) when it holds more
    // than `keepBytes`: called between renders, so a large one lives for one render only.
    void trimCameraImages(size_t keepBytes) { camera_.trimImages(keepBytes); }

    // ---- the ray tracer's scene (no GL; any thread) ----
    // The one Embree BVH of this scene's geometry: the reference, refinement and the sparse check
    // all trace it. Built on first use, rebuilt after a mesh edit (not a light or camera edit);
    // builds() counts the builds.
    TraceSceneCache& traceScenes() { return traceScenes_; }
    const TraceSceneCache& traceScenes() const { return traceScenes_; }

    // ---- drawing (MeshDraws says what each draws) ----
    void drawMeshesWhere(const gl::Program& program, uint32_t requiredFlags,
                         const std::optional<PatchRegion>& region,
                         const std::function<void(const GpuMesh&)>& before, int castingFor = -1,
                         bool skipSeeThrough = false);
    void drawSeeThroughWhere(const gl::Program& program, uint32_t requiredFlags,
                             const std::function<void(const GpuMesh&)>& before, int castingFor = -1);
    // Where each of the scene's meshes is now (what a pass drawn now shows: movedBoxes).
    std::vector<MeshPlacement> placements() const { return placementsOf(*scene_); }
    // Draws one triangle covering the viewport (vertex shader "common/fullscreen.vert.glsl").
    void drawFullscreen();

    // ---- uniform binders (shader_uniforms.cpp) ----
    // Binds the camera pass textures to units firstUnit.. and sets the samplers of
    // "common/camera_gbuffer.glsl" (uCamPositionDepth, uCamNormalReceive, uCamIds).
    // Returns the next free texture unit.
    int bindCameraPass(const gl::Program& program, int firstUnit = 0);
    // Sets the uLight uniforms of "common/light.glsl" for light `lightIndex`.
    void setLightUniforms(const gl::Program& program, int lightIndex) const;
    // Sets uShadowDistance (texture) and uShadow* of "common/shadow_map.glsl"; returns next unit.
    int bindShadowMap(const gl::Program& program, const ShadowMap& map, int unit) const;

    const SceneCacheStats& stats() const { return stats_; }

private:
    // What the drawing of a pass reads: the meshes as the scene is now (uploaded first, so their
    // upload is timed apart from the pass).
    MeshDraws draws();
    // Drops the camera pass and shadow maps whose inputs changed since they were drawn; after
    // moves alone the passes are kept and patched where the moved meshes were and are.
    void dropStalePasses();
    const Scene* scene_;
    SceneCacheStats stats_;
    GpuMeshes meshes_;
    EmptyVertexArray emptyVertexArray_;
    CameraPassCache camera_;
    ShadowMapCache shadowMaps_;
    TraceSceneCache traceScenes_;
};

}  // namespace ss
