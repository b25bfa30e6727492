// How the reference traces a list of pixels: one camera ray each, the reference's light samples.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/trace_pixels.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

#include "core/error.h"
#include "reference/adaptive_sampling.h"
#include "reference/camera_rays.h"
#include "reference/light_sampler.h"
#include "reference/visibility_estimator.h"

namespace ss {

std::vector<PixelVisibility> tracePixels(const TraceScene& trace, const Scene& scene, int lightIndex,
                                         const std::vector<std::pair<int, int>>& pixels, int samples,
                                         uint32_t seed, const AdaptiveSampling* adaptive) {
    const Light& light = scene.light(lightIndex);
    const Camera& camera = scene.camera();
    const CameraRays rays(camera);
    const LightSampler sampler(light);
    std::vector<PixelVisibility> out(pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i) {
        auto [x, y] = pixels[i];
        if (x < 0 || y < 0 || x >= camera.width || y >= camera.height)
            fail(SS_ERROR_INVALID_ARGUMENT, "tracePixels: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                                ") is outside the " + std::to_string(camera.width) + "x" +
                                                std::to_string(camera.height) + " image");
        out[i].x = x, out[i].y = y;
    }
    auto traceRange = [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            Ray ray;
            float tNear, tFar;
            if (!rays.span(out[i].x, out[i].y, &ray, &tNear, &tFar)) continue;
            SurfaceHit hit = trace.intersect(ray, tNear, tFar);
            if (!hit.hit || !scene.receivesFrom(int(hit.mesh), lightIndex)) continue;
            out[i].mesh = int(hit.mesh);
            SampleSequence sequence(seed, uint32_t(out[i].x), uint32_t(out[i].y));
            out[i].centreVisible = lightCentreVisible(trace, sampler, hit, light.castShadows);
            if (adaptive) {
                SampleSums sums;
                sampleAdaptively(trace, sampler, hit, sequence, light.castShadows, *adaptive, &sums);
                if (!(sums.weight > 0.0)) continue;
                out[i].visibility = float(sums.visibility());
                out[i].inMask = true;
                continue;
            }
            PointVisibility pv = estimateVisibility(trace, sampler, hit, sequence, samples, light.castShadows);
            if (!pv.reached) continue;
            out[i].visibility = pv.visibility;
            out[i].inMask = true;
        }
    };
    // Every pixel depends on (seed, x, y) alone, so splitting the list changes nothing but speed.
    const size_t n = std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 8);
    const size_t chunk = (out.size() + n - 1) / n;
    std::vector<std::thread> workers;
    std::exception_ptr error;
    std::mutex mutex;
    for (size_t t = 0; t < n && t * chunk < out.size(); ++t)
        workers.emplace_back([&, t] {
            try {
                traceRange(t * chunk, std::min(out.size(), (t + 1) * chunk));
            } catch (...) {
                std::lock_guard lock(mutex);
                if (!error) error = std::current_exception();
            }
        });
    for (std::thread& w : workers) w.join();
    if (error) std::rethrow_exception(error);
    return out;
}

}  // namespace ss
