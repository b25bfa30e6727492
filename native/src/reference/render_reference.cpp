// How the reference image is traced: one camera ray per pixel centre, rows shared by all cores.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/render_reference.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/libstdcxx_baseline.h"
#include "reference/camera_rays.h"
#include "reference/light_sampler.h"
#include "reference/visibility_estimator.h"

namespace ss {
namespace {

int threadCount(const RenderSettings& settings, int rows) {
    int n = settings.integer("threads", 0, 0, 1024);
    if (n <= 0) n = int(std::max(1u, std::thread::hardware_concurrency()));
    return std::clamp(n, 1, std::max(1, rows));
}

}  // namespace

Layers renderReference(const Scene& scene, int lightIndex, const RenderSettings& settings,
                       TraceSceneCache* cache) {
    const Light& light = scene.light(lightIndex);
    const Camera& camera = scene.camera();
    const int samples = settings.samples > 0 ? settings.samples : kReferenceDefaultSamples;
    // One pixel's rays are gathered before tracing (~25 bytes each per thread): cap the memory.
    if (samples > (1 << 20))
        fail(SS_ERROR_INVALID_ARGUMENT, "reference: " + std::to_string(samples) +
                                            " samples per pixel is more than 2^20");

    settings.report(0.0f, "building the ray-tracing scene");
    std::shared_ptr<const TraceScene> trace =
        cache ? cache->get(scene) : std::make_shared<const TraceScene>(scene);
    const LightSampler sampler(light);
    const CameraRays rays(camera);
    const int width = camera.width, height = camera.height;
    Image visibility(width, height, 1.0f), mask(width, height, 0.0f);

    auto renderRow = [&](int y) {
        for (int x = 0; x < width; ++x) {
            Ray ray;
            float tNear, tFar;
            if (!rays.span(x, y, &ray, &tNear, &tFar)) continue;
            SurfaceHit hit = trace->intersect(ray, tNear, tFar);
            if (!hit.hit || !scene.meshes()[hit.mesh].receives()) continue;
            SampleSequence sequence(settings.seed, uint32_t(x), uint32_t(y));
            PointVisibility pv =
                estimateVisibility(*trace, sampler, hit, sequence, samples, light.castShadows);
            if (!pv.reached) continue;
            visibility.at(x, y) = pv.visibility;
            mask.at(x, y) = 1.0f;
        }
    };

    // Workers take rows from a counter; the calling thread only reports progress, so the
    // progress callback (which may be Python) is never called from a worker.
    std::atomic<int> nextRow{0}, rowsDone{0};
    std::atomic<bool> stop{false};
    std::mutex mutex;
    std::condition_variable finished;
    int workersLeft = threadCount(settings, height);
    std::exception_ptr error;
    std::vector<std::thread> workers;
    for (int t = 0, n = workersLeft; t < n; ++t)
        workers.emplace_back([&] {
            try {
                for (int y; !stop && (y = nextRow++) < height; ++rowsDone) renderRow(y);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex);
                if (!error) error = std::current_exception();
                stop = true;
            }
            std::lock_guard<std::mutex> lock(mutex);
            if (--workersLeft == 0) finished.notify_all();
        });
    auto joinAll = [&] {
        for (std::thread& w : workers) w.join();
    };
    try {
        std::unique_lock<std::mutex> lock(mutex);
        while (workersLeft > 0) {
            finished.wait_for(lock, std::chrono::milliseconds(50));
            if (workersLeft == 0) break;
            lock.unlock();
            settings.report(float(rowsDone) / float(height), "tracing shadow rays");
            lock.lock();
        }
    } catch (...) {
        stop = true;
        joinAll();
        throw;
    }
    joinAll();
    if (error) std::rethrow_exception(error);
    settings.report(1.0f, "tracing shadow rays");

    Layers layers;
    layers.add("V", std::move(visibility));
    layers.add("mask", std::move(mask));
    return layers;
}

}  // namespace ss
