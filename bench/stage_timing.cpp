// How one cold frame of a method is timed stage by stage: glFinish closes every GL stage.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "stage_timing.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>

#include "core/stopwatch.h"
#include "gl/render_thread.h"
#include "methods/method.h"
#include "scene_cache/scene_cache.h"

namespace ss::bench {

namespace {
gl::RenderThread& glThread() {
    static gl::RenderThread* t = new gl::RenderThread(SS_BACKEND_AUTO);
    return *t;
}

}  // namespace

// One cold frame: every shared pass drawn afresh, then the method's prepare and render. glFinish
// after each GL stage, so the time lands on the stage that queued the work (llvmpipe defers).
Stages runOnce(const Scene& scene, const std::string& method, Layers* keep, double budgetSeconds,
               const std::map<std::string, std::string>& options, int samples) {
    Stages st;
    std::unique_ptr<Method> m = createMethod(method);
    RenderSettings settings;
    settings.options = options;
    settings.samples = samples;
    // V and mask only: what a preview or a compositing pass needs; the debug layers' read-backs
    // would weigh on the methods that have many (dbuffer's four distances cost ~30 ms at 1024²).
    settings.extraLayers = false;
    if (budgetSeconds > 0.0) {
        auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(budgetSeconds));
        settings.progress = [deadline](float, const char*) { return Clock::now() < deadline; };
    }
    if (!m->needsGl()) {
        SceneCache sceneCache(scene);
        auto t = Clock::now();
        m->prepare(sceneCache, 0, settings);
        st.prepare = msSince(t);
        t = Clock::now();
        Layers out = m->render(sceneCache, 0, settings);
        st.render = msSince(t);
        if (keep) *keep = std::move(out);
        return st;
    }
    glThread().run([&] {
        SceneCache sceneCache(scene);
        const gl::Functions& g = sceneCache.gl();
        auto t = Clock::now();
        sceneCache.meshes();
        g.Finish();
        st.meshUpload = msSince(t);
        t = Clock::now();
        const CameraPass& cam = sceneCache.cameraPass();
        g.Finish();
        st.cameraPass = msSince(t);
        t = Clock::now();
        sceneCache.shadowMap(0);
        g.Finish();
        st.shadowMap = msSince(t);
        t = Clock::now();
        m->prepare(sceneCache, 0, settings);
        g.Finish();
        st.prepare = msSince(t);
        t = Clock::now();
        Layers out = m->render(sceneCache, 0, settings);
        st.render = msSince(t);
        if (keep) *keep = std::move(out);
        // What one float layer at camera resolution costs to bring back (every method reads at
        // least V; its own read-back is inside `render`).
        t = Clock::now();
        std::vector<Image> v = cam.framebuffer.readChannels(0, 1);
        st.readback = msSince(t);
        benchmark::DoNotOptimize(v);
        m.reset();  // GL objects of the method die on their own thread
    });
    return st;
}

}  // namespace ss::bench
