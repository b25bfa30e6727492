// The light-centre shadow maps one scene keeps: one per (light version, size), patched after
// moves that keep the scene's bounds, the least recently used dropped past a byte budget.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/scene.h"
#include "scene_cache/cache_counters.h"
#include "scene_cache/mesh_draws.h"
#include "scene_cache/moved_region.h"
#include "scene_cache/shadow_map.h"

namespace ss {

// The bytes the maps hold are SceneCacheStats::shadowMapBytes (the budget's measure).
class ShadowMapCache {
public:
    // After the geometry changed: moves that leave the scene's bounds (so every map's fit) as
    // they were give each map the boxes to redraw at its next use; anything else drops them all.
    void dropStaleGeometry(const Scene& scene, SceneCacheStats& stats);
    // Drops the maps of lights edited or removed since (they are never asked for again).
    void dropEditedLights(const Scene& scene, SceneCacheStats& stats);
    // The scene bounds the maps are fit to (as of the last dropStaleGeometry).
    const Bounds& sceneBounds() const { return sceneBounds_; }
    // Light `lightIndex`'s map of `size` texels fit to `fit`: kept, patched where meshes moved,
    // or drawn afresh (also when its fit changed). The reference stays valid until the next trim.
    const ShadowMap& get(const Light& light, int lightIndex, int size, const Bounds& fit,
                         const MeshDraws& draws);
    // Drops the least recently used maps until the rest fit in `budgetBytes`.
    void trim(size_t budgetBytes, SceneCacheStats& stats);

private:
    // Draws the map's casters into its own targets, inside `rect` only when one is given.
    void draw(ShadowMap& map, int lightIndex, const std::optional<PixelRect>& rect, const MeshDraws& draws);
    struct Entry {
        std::unique_ptr<ShadowMap> map;
        uint64_t lastUse = 0;
        size_t bytes = 0;
        std::vector<Bounds> pending;  // world boxes moved meshes touched since it was drawn
        Bounds fit;                   // the box it was fit to (shadowFitBounds)
    };
    std::map<std::pair<uint64_t, int>, Entry> maps_;  // (Light::version, size)
    uint64_t useClock_ = 0;
    uint64_t geometry_ = 0;                  // the geometry the maps show
    std::vector<MeshPlacement> placements_;  // (with their pending boxes)
    Bounds sceneBounds_;                     // the scene bounds the maps are fit to
};

}  // namespace ss
