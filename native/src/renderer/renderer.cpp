// How a (light, method) render is dispatched: lazy GL start, the scene caches, CPU vs GL methods.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "renderer/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "core/stopwatch.h"
#include "core/visibility_classes.h"
#include "gl/capabilities.h"
#include "gl/context.h"
#include "gl/render_thread.h"
#include "gl/scratch_targets.h"
#include "scene_cache/scene_cache.h"
#include "methods/sparse_check.h"
#include "renderer/auto_method.h"
#include "renderer/refinement.h"
#include "renderer/render_memory.h"
#include "renderer/scene_in_range.h"
#include "renderer/unlit_receivers.h"

namespace ss {

struct Renderer::Impl {
    ss_backend backend;
    std::mutex m;  // one render at a time per renderer: scene caches and methods are not thread-safe
    std::unique_ptr<gl::RenderThread> thread;
    std::string infoJson;

    // The shared passes of a scene and the method objects with what they prepared, all kept
    // across its edits: the scene cache redraws only what an edit changed, and a method rebuilds its
    // geometry only when its light's key changes (Scene::lightGeometryKey).
    struct Cached {
        uint64_t sceneId = 0;
        std::unique_ptr<SceneCache> sceneCache;
        std::map<std::string, std::unique_ptr<Method>> methods;
    };
    // The scenes rendered last, least recent first: three, so that the add-on's two preview
    // scenes (coarse and full size, each with its own camera pass) and its render_passes scene
    // (one context) do not evict each other.
    static constexpr size_t kKeptScenes = 3;
    // The CPU copy of a camera pass (sweep's) and each scratch target kept from one render to
    // the next: up to 64 MiB (a 1920 x 720 preview's camera images, a 2048² RGBA32F target);
    // larger ones are made again for each render instead.
    static constexpr size_t kKeptCameraImagesBytes = size_t(64) << 20;
    std::vector<std::unique_ptr<Cached>> caches;
    CacheStats finished;  // of scene caches already dropped (and every method run's time)
    ScenesInRange inRange;  // the scenes without their meshes beyond the scene range
    size_t shadowMapBudget = SceneCache::kDefaultShadowMapBudget;

    void count(const Cached& c, CacheStats& into) const {
#define SS_ADD(type, member, name, combine, doc) into.member = combineCounter##combine(into.member, from.member);
        for (const auto& [name, method] : c.methods) {
            const MethodStats& from = method->stats();
            SS_METHOD_COUNTERS(SS_ADD)
        }
        const SceneCache& f = *c.sceneCache;
        const SceneCacheStats& from = f.stats();
        SS_SCENE_CACHE_COUNTERS(SS_ADD)
#undef SS_ADD
        into.traceSceneBuilds += f.traceScenes().builds();
        into.meshBvhBuilds += f.traceScenes().meshBvhBuilds();
    }

    // ss_shutdown() stopped the thread: everything GL died with its context, so the scene
    // caches go too and the next GL use starts afresh. Called only before any cache reference
    // is taken, since it may drop the caches.
    void forgetStoppedThread() {
        if (thread && !thread->running()) {
            dropCache();
            thread.reset();
            infoJson.clear();
        }
    }

    // The thread, started if there is none. A thread stopped by a shutdown since the last
    // forgetStoppedThread() is kept as it is: its run() throws SS_ERROR_GL, so a render that
    // already holds cache references fails cleanly instead of having them freed under it.
    gl::RenderThread& glThread() {
        if (!thread) thread = std::make_unique<gl::RenderThread>(backend);
        return *thread;
    }

    // GL objects are deleted on the thread that owns their context; off it (after shutdown)
    // their handles just forget them.
    template <class Doomed>
    void destroyOnGlThread(Doomed& doomed) {
        if (thread && thread->running()) {
            try {
                thread->run([&] { doomed = Doomed(); });
            } catch (const Error&) {
                // Shut down in between: the context is gone and the handles just forget.
            }
        }
        doomed = Doomed();
    }

    void dropCache() {
        for (auto& c : caches) count(*c, finished);
        destroyOnGlThread(caches);
    }

    void dropOldest() {
        std::unique_ptr<Cached> oldest = std::move(caches.front());
        caches.erase(caches.begin());
        count(*oldest, finished);
        destroyOnGlThread(oldest);
    }

    // The scene's method object of that name, made once (its settings were checked against
    // renderSettingTable before any work).
    Method& method(const Scene& scene, const std::string& name) {
        auto& cached = cacheFor(scene);
        auto it = cached.methods.find(name);
        if (it == cached.methods.end()) it = cached.methods.emplace(name, createMethod(name)).first;
        return *it->second;
    }

    // Refinement of `layers`, method `name`'s result; each round but the last goes to `rounds`
    // (when set) with its class layers and, where `check` is given, its estimate.
    Refinement refine(const Scene& scene, int lightIndex, const std::string& name, const RenderSettings& settings,
                      Layers& layers, const SparseCheck* check, const RoundFn& rounds) {
        RefinementRoundFn landed;
        if (rounds)
            landed = [&](RefinementRound& r) {
                RoundResult partial{name, std::move(r.layers), std::numeric_limits<double>::quiet_NaN(), r.round,
                                    r.rounds};
                if (check) partial.estimatedRmse = estimatedRmse(*check, partial.layers, &r.traced, r.errorTarget);
                if (settings.extraLayers) addClassLayers(partial.layers);
                if (!rounds(partial))
                    fail(SS_ERROR_CANCELLED, "cancelled after refinement round " + std::to_string(r.round) + " of " +
                                                 std::to_string(r.rounds));
            };
        return refineUncertainPixels(scene, lightIndex, settings, cacheFor(scene).sceneCache->traceScenes(), layers, landed);
    }

    Cached& cacheFor(const Scene& scene) {
        for (size_t i = 0; i < caches.size(); ++i) {
            if (caches[i]->sceneId != scene.id()) continue;
            std::unique_ptr<Cached> c = std::move(caches[i]);
            caches.erase(caches.begin() + long(i));
            caches.push_back(std::move(c));
            Cached& cached = *caches.back();
            cached.sceneCache->setScene(scene);  // the same scene, perhaps moved in memory
            return cached;
        }
        if (caches.size() >= kKeptScenes) dropOldest();
        auto cached = std::make_unique<Cached>();
        cached->sceneId = scene.id();
        cached->sceneCache = std::make_unique<SceneCache>(scene);
        ++finished.sceneCaches;
        caches.push_back(std::move(cached));
        return *caches.back();
    }

    // Between renders, on the render thread: the current scene cache's stale passes go, the other
    // scenes' shadow maps (least recent scene first) give way until every kept map fits in the
    // budget beside the current scene's, which is then trimmed to the budget itself.
    void trimCaches(SceneCache& current) {
        current.dropStale();
        size_t others = 0;
        for (const auto& c : caches)
            if (c->sceneCache.get() != &current) others += c->sceneCache->shadowMapBytes();
        const size_t room = shadowMapBudget > current.shadowMapBytes() ? shadowMapBudget - current.shadowMapBytes() : 0;
        for (const auto& c : caches) {
            if (c->sceneCache.get() == &current || others <= room) continue;
            size_t held = c->sceneCache->shadowMapBytes();
            size_t excess = others - room;
            c->sceneCache->trimCache(held > excess ? held - excess : 0);
            others -= held - c->sceneCache->shadowMapBytes();
        }
        current.trimCache(shadowMapBudget);
        for (const auto& c : caches) c->sceneCache->trimCameraImages(kKeptCameraImagesBytes);
        gl::trimThreadScratchTargets(kKeptCameraImagesBytes);
    }
};

Renderer::Renderer(ss_backend backend) : impl_(std::make_unique<Impl>()) {
    gl::backendName(backend);  // throws for an unknown backend now, not at the first render
    impl_->backend = backend;
}

Renderer::~Renderer() {
    try {
        impl_->dropCache();
    } catch (...) {
        // A destructor must not throw; GL objects of a broken context are gone anyway.
    }
    impl_->thread.reset();
}

std::string Renderer::info() {
    std::lock_guard lock(impl_->m);
    if (impl_->infoJson.empty()) {
        impl_->forgetStoppedThread();
        gl::RenderThread& t = impl_->glThread();
        gl::Capabilities caps;
        t.run([&] { caps = gl::probeCapabilities(); });
        impl_->infoJson = caps.toJson(t.backendName(), t.device());
    }
    return impl_->infoJson;
}

void Renderer::setShadowMapBudget(size_t bytes) {
    std::lock_guard lock(impl_->m);
    impl_->shadowMapBudget = bytes;
}

Renderer::CacheStats Renderer::cacheStats() const {
    std::lock_guard lock(impl_->m);
    CacheStats s = impl_->finished;
    for (const auto& c : impl_->caches) impl_->count(*c, s);
    return s;
}

namespace {

void checkLayers(const Layers& layers, const Camera& camera, const std::string& method) {
    if (!layers.find("V") || !layers.find("mask"))
        fail(SS_ERROR_INTERNAL, "method '" + method + "' did not produce the V and mask layers");
    for (const char* reserved : {"umbra", "penumbra"})
        if (layers.find(reserved))
            fail(SS_ERROR_INTERNAL, "method '" + method + "' made the '" + reserved +
                                        "' layer, which the renderer draws from V for every method");
    for (const auto& [name, img] : layers.items)
        if (img.width != camera.width || img.height != camera.height ||
            img.pixels.size() != size_t(img.width) * size_t(img.height))
            fail(SS_ERROR_INTERNAL, "method '" + method + "' layer '" + name + "' is " +
                                        std::to_string(img.width) + "x" + std::to_string(img.height) +
                                        ", not the camera's " + std::to_string(camera.width) + "x" +
                                        std::to_string(camera.height));
}

}  // namespace

namespace {

// Taken by every method besides its own settings, read by the renderer (a CPU method: ignored).
constexpr SettingSpec kEstimateSetting =
    flagSetting("estimate_rmse", false, "estimate the pass's RMSE against rays at sparse pixels");

}  // namespace

SettingTable renderSettingTable(const std::string& method) {
    const SettingTable own = method == "auto" ? composed(autoSettingTable(), {kEstimateSetting})
                                              : composed(createMethod(method)->settingTable(), {kEstimateSetting});
    return composed(composed(own, refinementSettings()), {kMemoryLimitSetting});
}

Layers Renderer::renderMethod(const Scene& scene, int lightIndex, const std::string& name,
                              const RenderSettings& settings) {
    Method& m = impl_->method(scene, name);
    SceneCache& sceneCache = *impl_->cacheFor(scene).sceneCache;

    Layers layers;
    if (!m.needsGl()) {
        m.prepare(sceneCache, lightIndex, settings);
        layers = m.render(sceneCache, lightIndex, settings);
    } else {
        impl_->glThread().run([&] {
            impl_->trimCaches(sceneCache);
            const auto start = Clock::now();
            m.prepare(sceneCache, lightIndex, settings);
            layers = m.render(sceneCache, lightIndex, settings);
            impl_->finished.methodMs += msSince(start);
            if (scene.light(lightIndex).links.receivers)
                maskUnlitReceivers(scene, lightIndex, sceneCache.cameraImages(), layers);
        });
    }
    checkLayers(layers, scene.camera(), name);
    return layers;
}

bool Renderer::sparseCheck(const Scene& scene, int lightIndex, int pixels, int samples, uint32_t seed,
                           SparseCheck* out) {
    if (pixels <= 0) return false;
    try {
        std::shared_ptr<const TraceScene> trace = impl_->cacheFor(scene).sceneCache->traceScenes().get(scene, lightIndex);
        *out = runSparseCheck(*trace, scene, lightIndex, pixels, samples, seed);
    } catch (const Error& e) {
        if (e.status() == SS_ERROR_CANCELLED) throw;
        return false;  // no ray tracer for this scene: the caller falls back
    }
    return out->maskedPixels() > 0;
}

Layers Renderer::render(const Scene& given, int lightIndex, const std::string& method,
                        const RenderSettings& givenSettings, std::string* methodUsed, double* estimateOut,
                        AutoTrials* trialsOut, std::vector<std::string>* warnings, const RoundFn& rounds) {
    std::lock_guard lock(impl_->m);
    (void)given.camera();  // throws when the scene has no camera
    (void)given.light(lightIndex);  // throws for an index out of range, before any work
    RenderSettings settings = givenSettings;
    checkRenderMemory(given, lightIndex, method, settings);  // takes its own setting out
    const Scene& scene = impl_->inRange.forRender(given, lightIndex, warnings);
    impl_->forgetStoppedThread();
    settings.requireKnownKeys(method, renderSettingTable(method));
    SparseCheck check;
    bool checked = false;
    std::string name;
    Layers layers;
    AutoTrials trials;
    if (method == "auto") {
        const AutoCheckSize size = autoCheckSize(settings, scene.camera());
        settings.report(0.0f, "auto: tracing the sparse check");
        checked = sparseCheck(scene, lightIndex, size.pixels, size.samples, settings.seed, &check);
        const AutoMethods methods{
            [&](const std::string& candidate) -> const Method& { return impl_->method(scene, candidate); },
            [&](const std::string& candidate, const RenderSettings& own) {
                return renderMethod(scene, lightIndex, candidate, own);
            }};
        AutoChoice choice =
            chooseAutoMethod(scene, lightIndex, settings, checked ? &check : nullptr, methods, trials);
        name = std::move(choice.method), layers = std::move(choice.layers);
    } else {
        name = method;
        RenderSettings own = settings;
        own.options.erase(kEstimateSetting.key);
        // Made before the rounds, whose results carry the estimate too; a CPU method is exact.
        const Camera& camera = scene.camera();
        checked = settings.flag(kEstimateSetting) && impl_->method(scene, name).needsGl() &&
                  sparseCheck(scene, lightIndex, sparseCheckDefaultPixels(camera.width, camera.height), 0,
                              settings.seed, &check);
        layers = renderMethod(scene, lightIndex, name, own);
    }
    double estimate = std::numeric_limits<double>::quiet_NaN();
    // Refinement traces on the caller's thread (progress and rounds may call Python); the
    // reference is exact already, so it has nothing to refine.
    if (settings.refine && impl_->method(scene, name).needsGl()) {
        const Refinement r =
            impl_->refine(scene, lightIndex, name, settings, layers, checked ? &check : nullptr, rounds);
        if (checked) estimate = estimatedRmse(check, layers, &r.traced, r.errorTarget);
    } else if (checked) {
        estimate = estimatedRmse(check, layers);
    }
    if (settings.extraLayers) addClassLayers(layers);
    if (methodUsed) *methodUsed = name;
    if (estimateOut) *estimateOut = estimate;
    if (trialsOut) *trialsOut = std::move(trials);
    return layers;
}

}  // namespace ss
