// How the reference image is traced: one camera ray per pixel centre, rows shared by all cores, or adaptive rounds.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/render_reference.h"

#include <string>

#include "core/error.h"
#include "reference/adaptive_sampling.h"
#include "reference/camera_rays.h"
#include "reference/light_sampler.h"
#include "reference/parallel_rows.h"
#include "reference/visibility_estimator.h"

namespace ss {

namespace {

constexpr SettingSpec kAdaptive =
    flagSetting("adaptive", false, "sample in rounds until the error target (samples: the cap per pixel, default 1024)");

}  // namespace

const SettingTable& referenceSettings() {
    static const SettingTable table = composed({kThreadsSetting, kAdaptive}, adaptiveSamplingSettings());
    return table;
}

Layers renderReference(const Scene& scene, int lightIndex, const RenderSettings& settings,
                       TraceSceneCache* cache) {
    const Light& light = scene.light(lightIndex);
    const Camera& camera = scene.camera();
    const bool adaptive = settings.flag(kAdaptive);
    const int samples = settings.samples > 0 ? settings.samples
                        : adaptive        ? kReferenceAdaptiveDefaultSamples
                                          : kReferenceDefaultSamples;
    // One pixel's rays are gathered before tracing (~25 bytes each per thread): cap the memory.
    if (samples > (1 << 20))
        fail(SS_ERROR_INVALID_ARGUMENT, "reference: " + std::to_string(samples) +
                                            " samples per pixel is more than 2^20");

    settings.report(0.0f, "building the ray-tracing scene");
    std::shared_ptr<const TraceScene> trace =
        cache ? cache->get(scene, lightIndex)
              : std::make_shared<const TraceScene>(scene, std::vector<std::shared_ptr<const MeshBvh>>{}, lightIndex);
    if (adaptive) {
        const int width = camera.width, height = camera.height;
        Image visibility(width, height, 1.0f), mask(width, height, 0.0f), rays(width, height, 0.0f);
        traceAdaptive(scene, lightIndex, *trace, adaptiveSampling(settings, samples), settings, {},
                      {&visibility, &mask, &rays, nullptr});
        Layers layers;
        layers.add("V", std::move(visibility));
        layers.add("mask", std::move(mask));
        if (settings.extraLayers) layers.add("rays", std::move(rays));
        return layers;
    }
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
            if (!hit.hit || !scene.receivesFrom(int(hit.mesh), lightIndex)) continue;
            SampleSequence sequence(settings.seed, uint32_t(x), uint32_t(y));
            PointVisibility pv =
                estimateVisibility(*trace, sampler, hit, sequence, samples, light.castShadows);
            if (!pv.reached) continue;
            visibility.at(x, y) = pv.visibility;
            mask.at(x, y) = 1.0f;
        }
    };

    forEachRow(settings, height, "tracing shadow rays", 0.0f, 1.0f, renderRow);

    Layers layers;
    layers.add("V", std::move(visibility));
    layers.add("mask", std::move(mask));
    return layers;
}

}  // namespace ss
