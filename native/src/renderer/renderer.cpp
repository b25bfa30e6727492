// How a (light, method) render is dispatched: lazy GL start, the frame cache, CPU vs GL methods.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "renderer/renderer.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "core/visibility_classes.h"
#include "gl/capabilities.h"
#include "gl/context.h"
#include "gl/render_thread.h"
#include "frame/frame.h"
#include "reference/trace_scene_cache.h"
#include "renderer/refinement.h"

namespace ss {

struct Renderer::Impl {
    ss_backend backend;
    std::mutex m;  // one render at a time per renderer: frames and methods are not thread-safe
    std::unique_ptr<gl::RenderThread> thread;
    std::string infoJson;
    std::function<void()> cacheTakenHook;

    // The shared passes of a scene (kept across its edits: the frame redraws only what an edit
    // changed) and the method objects with whatever they prepared for its last revision.
    struct Cached {
        uint64_t sceneId = 0, revision = 0;
        std::unique_ptr<Frame> frame;
        std::map<std::string, std::unique_ptr<Method>> methods;
        TraceSceneCache refineTrace;  // the BVH of "refine=on", built at its first use
    };
    // The scenes rendered last, least recent first: two, so that the add-on's preview scene and
    // its render_passes scene (one context) do not evict each other.
    static constexpr size_t kKeptScenes = 2;
    std::vector<std::unique_ptr<Cached>> caches;
    CacheStats finished;  // of frames already dropped
    size_t shadowMapBudget = Frame::kDefaultShadowMapBudget;

    void count(const Frame& f, CacheStats& into) const {
        into.meshUploads += f.stats().meshUploads;
        into.cameraPasses += f.stats().cameraPasses;
        into.shadowMaps += f.stats().shadowMaps;
        into.shadowMapsEvicted += f.stats().shadowMapsEvicted;
        into.shadowMapBytesPeak = std::max(into.shadowMapBytesPeak, f.stats().shadowMapBytesPeak);
    }

    // ss_shutdown() stopped the thread: everything GL died with its context, so the frame
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
        for (auto& c : caches) count(*c->frame, finished);
        destroyOnGlThread(caches);
    }

    void dropOldest() {
        std::unique_ptr<Cached> oldest = std::move(caches.front());
        caches.erase(caches.begin());
        count(*oldest->frame, finished);
        destroyOnGlThread(oldest);
    }

    // Method objects may hold GL objects: freed on the render thread, like the frame's.
    void dropMethods(Cached& c) {
        std::map<std::string, std::unique_ptr<Method>> stale;
        stale.swap(c.methods);
        destroyOnGlThread(stale);
    }

    Cached& cacheFor(const Scene& scene) {
        for (size_t i = 0; i < caches.size(); ++i) {
            if (caches[i]->sceneId != scene.id()) continue;
            std::unique_ptr<Cached> c = std::move(caches[i]);
            caches.erase(caches.begin() + long(i));
            caches.push_back(std::move(c));
            Cached& cached = *caches.back();
            cached.frame->setScene(scene);  // the same scene, perhaps moved in memory
            if (cached.revision != scene.revision()) {
                dropMethods(cached);
                cached.revision = scene.revision();
            }
            return cached;
        }
        if (caches.size() >= kKeptScenes) dropOldest();
        auto cached = std::make_unique<Cached>();
        cached->sceneId = scene.id();
        cached->revision = scene.revision();
        cached->frame = std::make_unique<Frame>(scene);
        ++finished.frames;
        caches.push_back(std::move(cached));
        return *caches.back();
    }

    // Between renders, on the render thread: the current frame's stale passes go, the other
    // scenes' shadow maps (least recent scene first) give way until every kept map fits in the
    // budget beside the current frame's, which is then trimmed to the budget itself.
    void trimCaches(Frame& current) {
        current.dropStale();
        size_t others = 0;
        for (const auto& c : caches)
            if (c->frame.get() != &current) others += c->frame->shadowMapBytes();
        const size_t room = shadowMapBudget > current.shadowMapBytes() ? shadowMapBudget - current.shadowMapBytes() : 0;
        for (const auto& c : caches) {
            if (c->frame.get() == &current || others <= room) continue;
            size_t held = c->frame->shadowMapBytes();
            size_t excess = others - room;
            c->frame->trimCache(held > excess ? held - excess : 0);
            others -= held - c->frame->shadowMapBytes();
        }
        current.trimCache(shadowMapBudget);
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

void Renderer::setCacheTakenHook(std::function<void()> hook) {
    std::lock_guard lock(impl_->m);
    impl_->cacheTakenHook = std::move(hook);
}

void Renderer::setShadowMapBudget(size_t bytes) {
    std::lock_guard lock(impl_->m);
    impl_->shadowMapBudget = bytes;
}

Renderer::CacheStats Renderer::cacheStats() const {
    std::lock_guard lock(impl_->m);
    CacheStats s = impl_->finished;
    for (const auto& c : impl_->caches) impl_->count(*c->frame, s);
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

Layers Renderer::render(const Scene& scene, int lightIndex, const std::string& method,
                        const RenderSettings& settings, std::string* methodUsed) {
    std::lock_guard lock(impl_->m);
    const Camera& camera = scene.camera();  // throws when the scene has no camera
    (void)scene.light(lightIndex);  // throws for an index out of range, before any work
    std::string name = method == "auto" ? chooseAutoMethod(scene, lightIndex) : method;
    impl_->forgetStoppedThread();
    auto& cached = impl_->cacheFor(scene);
    auto it = cached.methods.find(name);
    if (it == cached.methods.end()) it = cached.methods.emplace(name, createMethod(name)).first;
    Method& m = *it->second;
    Frame& frame = *cached.frame;
    std::vector<std::string> keys = m.settingKeys();
    for (const std::string& k : refinementKeys())
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    settings.requireKnownKeys(name, keys);
    const bool refine = refinementRequested(settings);  // a bad value fails before any work
    if (impl_->cacheTakenHook) impl_->cacheTakenHook();

    Layers layers;
    if (!m.needsGl()) {
        m.prepare(frame, lightIndex, settings);
        layers = m.render(frame, lightIndex, settings);
    } else {
        impl_->glThread().run([&] {
            impl_->trimCaches(frame);
            m.prepare(frame, lightIndex, settings);
            layers = m.render(frame, lightIndex, settings);
        });
    }
    checkLayers(layers, camera, name);
    // Refinement traces on the caller's thread (progress may call Python); the reference is
    // exact already, so it has nothing to refine.
    if (refine && m.needsGl())
        refineUncertainPixels(scene, lightIndex, settings, cached.refineTrace, layers);
    if (settings.extraLayers) addClassLayers(layers);
    if (methodUsed) *methodUsed = name;
    return layers;
}

}  // namespace ss
