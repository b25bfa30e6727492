// How the adaptive rounds run: a first round everywhere, a guard band, then rounds until decided.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include "core/error.h"
#include "reference/camera_rays.h"
#include "reference/light_sampler.h"
#include "reference/parallel_rows.h"
#include "reference/sample_sequence.h"
#include "reference/visibility_estimator.h"

namespace ss {
namespace {

enum class PixelState : uint8_t { Skipped, Decided, Undecided };

// Agreement decides a pixel only when it rests on at least half a first round of rays: near the
// horizon one or two samples above it would decide the pixel alone.
bool decidedByAgreement(const SampleSums& s, const AdaptiveSampling& a) {
    return s.agree() && 2 * s.rays >= a.minSamples;
}

struct Tracer {
    const Scene& scene;
    const Light& light;
    const TraceScene& trace;
    const LightSampler sampler;
    const CameraRays rays;
    const uint32_t seed;

    // False when the pixel sees no receiving surface.
    bool surface(int x, int y, SurfaceHit* hit) const {
        Ray ray;
        float tNear, tFar;
        if (!rays.span(x, y, &ray, &tNear, &tFar)) return false;
        *hit = trace.intersect(ray, tNear, tFar);
        return hit->hit && scene.meshes()[hit->mesh].receives();
    }
    void add(const SurfaceHit& hit, int x, int y, uint32_t begin, uint32_t end, SampleSums* sums) const {
        addSamples(trace, sampler, hit, SampleSequence(seed, uint32_t(x), uint32_t(y)), begin, end,
                   light.castShadows, sums);
    }
};

// Rounds after the first until the point is decided; `sums` holds the first round's samples.
void continueRounds(const std::function<void(uint32_t, uint32_t, SampleSums*)>& add, const AdaptiveSampling& a,
                    float pixelTarget, SampleSums* sums) {
    int n = a.minSamples, passed = 0;
    while (n < a.maxSamples) {
        const int next = std::min(2 * n, a.maxSamples);
        const SampleSums before = *sums;
        add(uint32_t(n), uint32_t(next), sums);
        n = next;
        const double roundWeight = sums->weight - before.weight;
        if (!(before.weight > 0.0) || !(roundWeight > 0.0)) continue;
        const double roundV = (sums->visible - before.visible) / roundWeight;
        const double error = 0.5 * std::abs(before.visibility() - roundV);
        passed = error <= pixelTarget ? passed + 1 : 0;
        if (passed >= (decidedByAgreement(*sums, a) ? 1 : 2)) break;
    }
}

}  // namespace

float pixelErrorTarget(const AdaptiveSampling& a, size_t maskPixels, size_t undecidedPixels) {
    if (undecidedPixels == 0) return a.errorTarget;
    const double spread = std::sqrt(double(maskPixels) / double(undecidedPixels));
    return std::max(a.errorTarget, std::min(float(a.errorTarget * spread), AdaptiveSampling::kMaxPixelError));
}

void sampleAdaptively(const TraceScene& trace, const LightSampler& sampler, const SurfaceHit& hit,
                      const SampleSequence& sequence, bool castShadows, const AdaptiveSampling& sampling,
                      SampleSums* sums) {
    auto add = [&](uint32_t begin, uint32_t end, SampleSums* into) {
        addSamples(trace, sampler, hit, sequence, begin, end, castShadows, into);
    };
    add(0, uint32_t(sampling.minSamples), sums);
    if (!(sums->weight > 0.0) || decidedByAgreement(*sums, sampling)) return;
    // An isolated point has no image to share the error with: it keeps the target itself.
    continueRounds(add, sampling, sampling.errorTarget, sums);
}

std::vector<std::string> adaptiveSamplingKeys() { return {"error_target", "guard_band"}; }

AdaptiveSampling adaptiveSampling(const RenderSettings& settings, int maxSamples) {
    AdaptiveSampling a;
    a.maxSamples = maxSamples;
    a.minSamples = std::min(a.minSamples, maxSamples);
    a.errorTarget = settings.number("error_target", a.errorTarget, 1e-4f, 0.5f);
    a.guardBand = settings.integer("guard_band", a.guardBand, 0, 16);
    return a;
}

void traceAdaptive(const Scene& scene, int lightIndex, const TraceScene& trace,
                   const AdaptiveSampling& sampling, const RenderSettings& settings,
                   const Image* select, Image* visibility, Image* mask, Image* rays) {
    const Camera& camera = scene.camera();
    const int width = camera.width, height = camera.height;
    const Light& light = scene.light(lightIndex);
    const Tracer t{scene, light, trace, LightSampler(light), CameraRays(camera), settings.seed};
    const size_t count = size_t(width) * size_t(height);
    std::vector<PixelState> state(count, PixelState::Skipped);
    std::vector<SampleSums> sums(count);
    auto selected = [&](int x, int y) { return !select || select->at(x, y) != 0.0f; };

    // First round everywhere selected.
    forEachRow(settings, height, "tracing shadow rays (first round)", 0.0f, 0.3f, [&](int y) {
        for (int x = 0; x < width; ++x) {
            SurfaceHit hit;
            if (!selected(x, y) || !t.surface(x, y, &hit)) continue;
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            t.add(hit, x, y, 0, uint32_t(sampling.minSamples), &sums[i]);
            const bool decided = !(sums[i].weight > 0.0) || decidedByAgreement(sums[i], sampling);
            state[i] = decided ? PixelState::Decided : PixelState::Undecided;
        }
    });

    // The guard band: a decided pixel near one that disagrees takes the further rounds too.
    std::vector<PixelState> next = state;
    const int g = sampling.guardBand;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (state[size_t(y) * size_t(width) + size_t(x)] != PixelState::Undecided) continue;
            for (int v = std::max(0, y - g); v <= std::min(height - 1, y + g); ++v)
                for (int u = std::max(0, x - g); u <= std::min(width - 1, x + g); ++u) {
                    PixelState& s = next[size_t(v) * size_t(width) + size_t(u)];
                    if (s == PixelState::Decided) s = PixelState::Undecided;
                }
        }
    state.swap(next);
    size_t maskPixels = sampling.untracedMaskPixels, undecided = 0;
    for (size_t i = 0; i < count; ++i) {
        if (state[i] == PixelState::Undecided) ++undecided;
        if (state[i] != PixelState::Skipped && sums[i].weight > 0.0) ++maskPixels;
    }
    const float pixelTarget = pixelErrorTarget(sampling, maskPixels, undecided);

    forEachRow(settings, height, "tracing shadow rays (adaptive rounds)", 0.3f, 1.0f, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            if (state[i] == PixelState::Skipped) continue;
            if (state[i] == PixelState::Undecided) {
                SurfaceHit hit;
                t.surface(x, y, &hit);  // the same deterministic hit as the first round's
                continueRounds([&](uint32_t begin, uint32_t end, SampleSums* into) { t.add(hit, x, y, begin, end, into); },
                               sampling, pixelTarget, &sums[i]);
            }
            if (rays) rays->at(x, y) = float(sums[i].rays);
            if (!(sums[i].weight > 0.0)) continue;
            visibility->at(x, y) = float(sums[i].visible / sums[i].weight);
            if (mask) mask->at(x, y) = 1.0f;
        }
    });
}

}  // namespace ss
