// How one (light, method) render is run: the GL render thread, the scene caches, the checks.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "methods/method.h"
#include "renderer/auto_method.h"
#include "renderer/cache_stats.h"
#include "renderer/refinement.h"
#include "softshadow/softshadow.h"

namespace ss {

// Every setting render() accepts for `method` ("auto" included): the method's table (auto's:
// autoSettingTable), then estimate_rmse, refinement's (renderer/refinement.h) and
// memory_limit_mb. Throws ss::Error(SS_ERROR_INVALID_ARGUMENT) for an unknown method.
SettingTable renderSettingTable(const std::string& method);

// Owns (lazily) the GL context on the library's own render thread and the per-scene cache of
// shared passes (mesh buffers, the camera pass, one light-centre shadow map per light), so that
// a series of render() calls on the same scene draws each shared pass once and, after an edit,
// redraws only what the edit changed (see SceneCache).
// CPU-only methods (reference) never start GL.
class Renderer {
public:
    explicit Renderer(ss_backend backend);
    ~Renderer();  // not copyable: it owns a GL thread and caches through impl_

    // Starts GL if needed; throws ss::Error(SS_ERROR_GL) naming every backend tried.
    // JSON: {"backend", "renderer", "vendor", "version", "limits": {...}}.
    std::string info();

    // What `auto` did for one render (renderer/auto_method.h). Empty for any other method.
    using AutoTrials = ss::AutoTrials;

    // `method` may be "auto"; *methodUsed receives the method that ran. *estimatedRmse (may be
    // null) receives the result's expected RMSE against the reference from the sparse exact
    // check (methods/sparse_check.h), or NaN where none was made: `auto` always makes one, any
    // other GL method when the setting "estimate_rmse=1" asks for it (a CPU method: never).
    // "auto" chooses as chooseAutoMethod (renderer/auto_method.h) says.
    // Meshes beyond the scene range (core/scene_range.h) are left out, one message each in
    // *warnings (may be null); a light or camera beyond it, or a render past the memory budget
    // (renderer/render_memory.h), fails before any work.
    // With settings.refine and refineRounds = n > 1 (renderer/refinement.h), `rounds` (may be
    // empty) hears each round but the last, on the caller's thread, while the render holds the
    // renderer; it returns false to cancel (SS_ERROR_CANCELLED).
    struct RoundResult {
        std::string method;  // the method that ran ("auto" resolved)
        Layers layers;       // as refined so far; with extraLayers the class layers too
        double estimatedRmse = 0.0;  // as the result's, NaN where the render makes none
        int round = 0, rounds = 0;   // 1-based
    };
    using RoundFn = std::function<bool(RoundResult& partial)>;
    Layers render(const Scene& scene, int lightIndex, const std::string& method,
                  const RenderSettings& settings, std::string* methodUsed,
                  double* estimatedRmse = nullptr, AutoTrials* trials = nullptr,
                  std::vector<std::string>* warnings = nullptr, const RoundFn& rounds = {});

    // What the caches did over the renderer's life (scene_cache/cache_counters.h lists the counters;
    // tests of the scene caches and the benchmark's stage counts read them).
    using CacheStats = ss::CacheStats;
    CacheStats cacheStats() const;

    // What the cached shadow maps may hold between renders (least recently used go first);
    // default SceneCache::kDefaultShadowMapBudget.
    void setShadowMapBudget(size_t bytes);

private:
    // One method as it is (settings keys checked), with the scene cache and GL thread; not refined.
    Layers renderMethod(const Scene& scene, int lightIndex, const std::string& name,
                        const RenderSettings& settings);
    // The sparse exact check of the light; false where it cannot be made (no pixel, no ray
    // tracer, no checked pixel the light reaches).
    bool sparseCheck(const Scene& scene, int lightIndex, int pixels, int samples, uint32_t seed,
                     SparseCheck* out);
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace ss
