// How a scene's shadow maps are kept: drawn, patched after moves, dropped when stale or past the
// budget.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/shadow_map_cache.h"

#include <algorithm>

#include "core/stopwatch.h"
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/render_state.h"
#include "scene_cache/shader_uniforms.h"

namespace ss {

void ShadowMapCache::dropStaleGeometry(const Scene& scene, SceneCacheStats& stats) {
    const uint64_t geometry = scene.geometryVersion();
    if (geometry_ == geometry) return;
    std::vector<MeshPlacement> now = placementsOf(scene);
    const Bounds bounds = scene.bounds();
    std::optional<std::vector<Bounds>> moved = movedBoxes(placements_, now);
    // A map is fit to the scene bounds: when they change, so does every map's frustum.
    const bool sameFit = bounds.lo == sceneBounds_.lo && bounds.hi == sceneBounds_.hi;
    if (moved && sameFit) {
        for (auto& entry : maps_)
            entry.second.pending.insert(entry.second.pending.end(), moved->begin(), moved->end());
    } else {
        for (auto& entry : maps_) stats.shadowMapBytes -= entry.second.bytes;
        maps_.clear();
    }
    placements_ = std::move(now);
    sceneBounds_ = bounds;
    geometry_ = geometry;
}

void ShadowMapCache::dropEditedLights(const Scene& scene, SceneCacheStats& stats) {
    for (auto it = maps_.begin(); it != maps_.end();) {
        bool current = false;
        for (const Light& l : scene.lights()) current = current || l.version == it->first.first;
        if (current) {
            ++it;
        } else {
            stats.shadowMapBytes -= it->second.bytes;
            it = maps_.erase(it);
        }
    }
}

void ShadowMapCache::draw(ShadowMap& map, int lightIndex, const std::optional<PixelRect>& rect,
                          const MeshDraws& draws) {
    const gl::Functions& g = gl::api();
    gl::Framebuffer fb(map.size, map.size, {});
    fb.attachColor(0, map.distance.id());
    fb.attachDepth(map.depth.id());
    fb.bind();
    scissorTo(g, rect);
    fb.clearColor(0, glm::vec4(ShadowMap::kEmpty));
    fb.clearDepth(1.0f);
    // Casters nearer the light than the near plane (beyond the fit box, towards the light)
    // still shadow: clamped onto it, they keep their true distance.
    gl::apply(gl::states::opaqueDepthClamped);
    const gl::Program& prog = gl::program("common/mesh.vert.glsl", "shadow_map/distance.frag.glsl");
    prog.use();
    prog.set("uWorldToClip", map.worldToClip());
    setShadowMapUniforms(prog, map);
    draws.drawWhere(prog, SS_MESH_CAST, patchRegion(rect, map.worldToClip(), map.size, map.size), {},
                    lightIndex, true);
    // See-through casters are alpha-tested (hashed): drawn whole, also in a patch (the scissor
    // keeps the rest of the map).
    const gl::Program& seeThrough =
        gl::program("shadow_map/see_through.vert.glsl", "shadow_map/see_through.frag.glsl");
    seeThrough.use();
    seeThrough.set("uWorldToClip", map.worldToClip());
    setShadowMapUniforms(seeThrough, map);
    draws.drawSeeThroughWhere(seeThrough, SS_MESH_CAST, {}, lightIndex);
    g.Disable(GL_SCISSOR_TEST);
    g.BindFramebuffer(GL_FRAMEBUFFER, 0);
    g.check("drawing a shadow map");
}

const ShadowMap& ShadowMapCache::get(const Light& light, int lightIndex, int size, const Bounds& fit,
                                     const MeshDraws& draws) {
    SceneCacheStats& stats = draws.stats;
    auto key = std::make_pair(light.version, size);
    auto it = maps_.find(key);
    if (it != maps_.end() && !(it->second.fit.lo == fit.lo && it->second.fit.hi == fit.hi)) {
        // Fit around what the camera sees, and that moved: drawn afresh.
        stats.shadowMapBytes -= it->second.bytes;
        maps_.erase(it);
        it = maps_.end();
    }
    if (it != maps_.end()) {
        Entry& entry = it->second;
        entry.lastUse = ++useClock_;
        if (!entry.pending.empty()) {
            // Moves since it was drawn (the fit is the same: dropStaleGeometry checked the bounds).
            const auto start = Clock::now();
            ShadowMap& map = *entry.map;
            std::optional<PixelRect> rect =
                boxesOnScreen(entry.pending, map.worldToClip(), map.size, map.size);
            if (!rect || !rect->empty()) draw(map, lightIndex, rect, draws);
            if (rect) ++stats.shadowMapsPatched;
            entry.pending.clear();
            gl::api().Finish();
            stats.shadowMapMs += msSince(start);
            ++stats.shadowMaps;
        }
        return *entry.map;
    }
    const auto start = Clock::now();
    auto map = std::make_unique<ShadowMap>(fitShadowMap(light, fit, size));
    map->distance = gl::Texture(size, size, GL_R32F, GL_NEAREST);
    map->depth = gl::Texture(size, size, GL_DEPTH_COMPONENT32F, GL_NEAREST);
    draw(*map, lightIndex, std::nullopt, draws);
    gl::api().Finish();
    stats.shadowMapMs += msSince(start);
    ++stats.shadowMaps;
    Entry entry;
    entry.map = std::move(map);
    entry.lastUse = ++useClock_;
    entry.fit = fit;
    entry.bytes = size_t(size) * size_t(size) * (sizeof(float) + sizeof(float));  // R32F + depth 32F
    stats.shadowMapBytes += entry.bytes;
    stats.shadowMapBytesPeak = std::max(stats.shadowMapBytesPeak, stats.shadowMapBytes);
    return *maps_.emplace(key, std::move(entry)).first->second.map;
}

void ShadowMapCache::trim(size_t budgetBytes, SceneCacheStats& stats) {
    while (stats.shadowMapBytes > budgetBytes && !maps_.empty()) {
        auto oldest = maps_.begin();
        for (auto it = maps_.begin(); it != maps_.end(); ++it)
            if (it->second.lastUse < oldest->second.lastUse) oldest = it;
        stats.shadowMapBytes -= oldest->second.bytes;
        ++stats.shadowMapsEvicted;
        maps_.erase(oldest);
    }
}

}  // namespace ss
