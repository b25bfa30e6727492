// How the scene cache ties its parts together: which passes an edit leaves stale, and the order
// a pass needs the others in (meshes, then the camera pass, then the maps fit around it).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/scene_cache.h"

#include "core/error.h"

namespace ss {

SceneCache::SceneCache(const Scene& scene) : scene_(&scene) {}
SceneCache::~SceneCache() = default;

const Light& SceneCache::light(int index) const { return scene_->light(index); }

const gl::Functions& SceneCache::gl() const { return gl::api(); }

const std::vector<GpuMesh>& SceneCache::meshes() { return meshes_.update(*scene_, stats_); }

MeshDraws SceneCache::draws() { return MeshDraws{*scene_, meshes(), emptyVertexArray_, stats_}; }

void SceneCache::dropStalePasses() {
    camera_.dropStale(*scene_);
    shadowMaps_.dropStaleGeometry(*scene_, stats_);
}

const CameraPass& SceneCache::cameraPass() {
    dropStalePasses();
    return camera_.get(draws());
}

const CameraImages& SceneCache::cameraImages() {
    dropStalePasses();
    return camera_.images(draws());
}

const Bounds& SceneCache::receiversInView() {
    dropStalePasses();
    return camera_.receiversInView(draws());
}

Bounds SceneCache::shadowFitBounds(int lightIndex) {
    dropStalePasses();
    return ss::shadowFitBounds(light(lightIndex), shadowMaps_.sceneBounds(), receiversInView());
}

const ShadowMap& SceneCache::shadowMap(int lightIndex, int size) {
    if (size <= 0) size = kDefaultShadowMapSize;
    const Bounds fit = shadowFitBounds(lightIndex);  // drops the stale passes
    return shadowMaps_.get(light(lightIndex), lightIndex, size, fit, draws());
}

void SceneCache::trimCache(size_t budgetBytes) { shadowMaps_.trim(budgetBytes, stats_); }

void SceneCache::dropStale() {
    dropStalePasses();
    traceScenes_.dropStale(*scene_);
    shadowMaps_.dropEditedLights(*scene_, stats_);
}

void SceneCache::drawMeshesWhere(const gl::Program& program, uint32_t requiredFlags,
                                 const std::optional<PatchRegion>& region,
                                 const std::function<void(const GpuMesh&)>& before, int castingFor,
                                 bool skipSeeThrough) {
    draws().drawWhere(program, requiredFlags, region, before, castingFor, skipSeeThrough);
}

void SceneCache::drawSeeThroughWhere(const gl::Program& program, uint32_t requiredFlags,
                                     const std::function<void(const GpuMesh&)>& before, int castingFor) {
    draws().drawSeeThroughWhere(program, requiredFlags, before, castingFor);
}

void SceneCache::drawFullscreen() {
    const gl::Functions& g = gl();
    emptyVertexArray_.bind();
    g.DrawArrays(GL_TRIANGLES, 0, 3);
    g.BindVertexArray(0);
}

}  // namespace ss
