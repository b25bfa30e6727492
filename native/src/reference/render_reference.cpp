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
#include "reference/light_sampler.h"
#include "reference/visibility_estimator.h"

namespace ss {
namespace {

// The part of a pixel's ray between the camera's near and far planes, as GL (and Cycles'
// clip start/end) see it: the contract's pixel centre through Camera::pixelRay.
struct CameraRays {
    const Camera& camera;
    glm::mat4 clipToWorld;
    glm::vec3 eye;

    explicit CameraRays(const Camera& c)
        : camera(c), clipToWorld(glm::inverse(c.worldToClip())), eye(c.position()) {}

    glm::vec3 unproject(glm::vec2 ndc, float z) const {
        glm::vec4 p = clipToWorld * glm::vec4(ndc, z, 1.0f);
        return glm::vec3(p) / p.w;
    }

    // Returns false when the pixel's near/far span is empty or not finite.
    bool span(int x, int y, Ray* ray, float* tNear, float* tFar) const {
        float px = float(x) + 0.5f, py = float(y) + 0.5f;
        *ray = camera.pixelRay(px, py);
        glm::vec2 ndc(2.0f * px / float(camera.width) - 1.0f, 1.0f - 2.0f * py / float(camera.height));
        glm::vec3 a = unproject(ndc, -1.0f), b = unproject(ndc, 1.0f);
        if (camera.isOrthographic()) {
            *tNear = 0.0f;
            *tFar = glm::length(b - a);
        } else {
            *tNear = glm::length(a - eye);
            *tFar = glm::length(b - eye);
        }
        return std::isfinite(*tNear) && std::isfinite(*tFar) && *tFar > *tNear;
    }
};

int threadCount(const RenderSettings& settings, int rows) {
    int n = int(settings.number("threads", 0.0f));
    if (n <= 0) n = int(std::max(1u, std::thread::hardware_concurrency()));
    return std::clamp(n, 1, std::max(1, rows));
}

}  // namespace

Layers renderReference(const Scene& scene, int lightIndex, const RenderSettings& settings,
                       TraceSceneCache* cache) {
    if (lightIndex < 0 || lightIndex >= int(scene.lights().size()))
        fail(SS_ERROR_INVALID_ARGUMENT, "reference: light index " + std::to_string(lightIndex) +
                                            " is out of range (the scene has " +
                                            std::to_string(scene.lights().size()) + " lights)");
    const Camera& camera = scene.camera();
    const Light& light = scene.lights()[size_t(lightIndex)];
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
    if (settings.extraLayers) {
        Image umbra(width, height, 0.0f), penumbra(width, height, 0.0f);
        for (size_t i = 0; i < visibility.pixels.size(); ++i) {
            if (mask.pixels[i] == 0.0f) continue;
            float v = visibility.pixels[i];
            umbra.pixels[i] = v < kUmbraBelow ? 1.0f : 0.0f;
            penumbra.pixels[i] = (v >= kUmbraBelow && v <= kLitAbove) ? 1.0f : 0.0f;
        }
        layers.add("V", std::move(visibility));
        layers.add("mask", std::move(mask));
        layers.add("umbra", std::move(umbra));
        layers.add("penumbra", std::move(penumbra));
    } else {
        layers.add("V", std::move(visibility));
        layers.add("mask", std::move(mask));
    }
    return layers;
}

}  // namespace ss
