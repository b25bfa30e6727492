// How the adaptive rounds run: a first round everywhere, a guard band, then rounds until decided.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include "core/error.h"
#include "core/visibility_contract.h"
#include "reference/camera_rays.h"
#include "reference/light_sampler.h"
#include "reference/parallel_rows.h"
#include "reference/sample_sequence.h"
#include "reference/visibility_estimator.h"

namespace ss {
namespace {

// Outside: not to be traced. Selected: to take a first round. Reachable: not selected, but the
// guard band may reach it (it becomes Promoted). NoSurface: sees no receiving surface.
// Undecided pixels take further rounds and end Finished.
enum class PixelState : uint8_t { Outside, Selected, Reachable, Promoted, NoSurface, Decided, Undecided, Finished };

// Pixels of a wave per work item: the waves are short lists scattered over the image.
constexpr size_t kWaveChunk = 64;

// Agreement decides a pixel only when it rests on at least half a first round of rays: near the
// horizon one or two samples above it would decide the pixel alone.
bool decidedByAgreement(const SampleSums& s, const AdaptiveSampling& a) {
    return s.agree() && 2 * s.rays >= a.minSamples;
}

struct Tracer {
    const Scene& scene;
    const int lightIndex;
    const Light& light;
    const TraceScene& trace;
    const LightSampler sampler;
    const CameraRays rays;
    const uint32_t seed;
    TracedSamples* const kept;

    // False when the pixel sees no surface that receives this light (its mesh flags and light linking).
    bool surface(int x, int y, SurfaceHit* hit) const {
        Ray ray;
        float tNear, tFar;
        if (!rays.span(x, y, &ray, &tNear, &tFar)) return false;
        *hit = trace.intersect(ray, tNear, tFar);
        return hit->hit && scene.receivesFrom(int(hit->mesh), lightIndex);
    }
    void add(const SurfaceHit& hit, int x, int y, uint32_t begin, uint32_t end, SampleSums* sums) const {
        const size_t pixel = size_t(y) * size_t(rays.camera.width) + size_t(x);
        if (kept && kept->take(pixel, begin, end, sums)) return;
        addSamples(trace, sampler, hit, SampleSequence(seed, uint32_t(x), uint32_t(y)), begin, end,
                   light.castShadows, sums);
        if (kept) kept->keep(pixel, begin, end, *sums);
    }
};

// Rounds after the first until the point is decided; `sums` holds the first round's samples.
// A pixel whose rays all agree stops once the round passes the target and it has traced
// `agreeingRays` rays (the guard band's pixels: beside a disagreeing pixel, a faint penumbra may
// hide between a few rays); any other once the round passes the target and the round before
// was on track for it (kOnTrack). A round with fewer than minSamples / 2 rays in all (a surface
// almost turned away from the light) estimates nothing: two or three rays that agree say 0.
void continueRounds(const std::function<void(uint32_t, uint32_t, SampleSums*)>& add, const AdaptiveSampling& a,
                    float pixelTarget, int agreeingRays, SampleSums* sums) {
    int n = a.minSamples;
    bool previousOnTrack = false;
    while (n < a.maxSamples) {
        const int next = std::min(2 * n, a.maxSamples);
        const SampleSums before = *sums;
        add(uint32_t(n), uint32_t(next), sums);
        n = next;
        const double roundWeight = sums->weight - before.weight;
        if (!(before.weight > 0.0) || !(roundWeight > 0.0) || 2 * sums->rays < a.minSamples) continue;
        const double roundV = (sums->visible - before.visible) / roundWeight;
        const double error = 0.5 * std::abs(before.visibility() - roundV);
        const bool passes = error <= pixelTarget;
        if (decidedByAgreement(*sums, a) ? passes && sums->rays >= agreeingRays : passes && previousOnTrack) break;
        previousOnTrack = error <= AdaptiveSampling::kOnTrack * pixelTarget;
    }
}

}  // namespace

namespace {

bool sameSums(const SampleSums& a, const SampleSums& b) {
    return a.weight == b.weight && a.visible == b.visible && a.rays == b.rays && a.leastThrough == b.leastThrough &&
           a.mostThrough == b.mostThrough;
}

}  // namespace

bool TracedSamples::take(size_t pixel, uint32_t begin, uint32_t end, SampleSums* sums) const {
    const std::vector<Block>* blocks = blocks_[pixel].get();
    if (!blocks) return false;
    // The sums before the block must be what the kept blocks before it gave: the same samples
    // in the same order.
    bool startsHere = begin == 0 && sameSums(*sums, SampleSums{});
    for (const Block& b : *blocks) {
        if (b.begin == begin && b.end == end && startsHere) {
            *sums = b.after;
            return true;
        }
        if (b.end == begin && sameSums(b.after, *sums)) startsHere = true;
    }
    return false;
}

void TracedSamples::keep(size_t pixel, uint32_t begin, uint32_t end, const SampleSums& after) {
    std::unique_ptr<std::vector<Block>>& blocks = blocks_[pixel];
    if (!blocks) blocks = std::make_unique<std::vector<Block>>();
    blocks->push_back({begin, end, after});
}

int raysToTrustAgreement(float pixelTarget) {
    return int(std::ceil(2.0 / (std::exp(1.0) * double(pixelTarget))));
}

float pixelErrorTarget(const AdaptiveSampling& a, size_t maskPixels, size_t undecidedPixels) {
    if (undecidedPixels == 0) return a.errorTarget;
    const double spread = std::sqrt(double(maskPixels) / double(undecidedPixels));
    const float cap = std::min(AdaptiveSampling::kPenumbraShare * a.errorTarget, AdaptiveSampling::kMaxPixelError);
    return std::max(a.errorTarget, std::min(float(a.errorTarget * spread), cap));
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
    continueRounds(add, sampling, sampling.errorTarget, 0, sums);
}

namespace {

constexpr SettingSpec kErrorTarget =
    floatSetting("error_target", 0.01, 1e-4, 0.5, "RMS error of V the adaptive rounds aim at over the image");
constexpr SettingSpec kGuardBand =
    intSetting("guard_band", 2, 0, 16, "pixels around an undecided one that are sampled further too");

}  // namespace

const SettingTable& adaptiveSamplingSettings() {
    static const SettingTable table{kErrorTarget, kGuardBand};
    return table;
}

AdaptiveSampling adaptiveSampling(const RenderSettings& settings, int maxSamples) {
    AdaptiveSampling a;
    a.maxSamples = maxSamples;
    a.minSamples = std::min(a.minSamples, maxSamples);
    a.errorTarget = settings.number(kErrorTarget);
    a.guardBand = settings.integer(kGuardBand);
    return a;
}

void traceAdaptive(const Scene& scene, int lightIndex, const TraceScene& trace,
                   const AdaptiveSampling& sampling, const RenderSettings& settings,
                   const AdaptivePixels& pixels, const AdaptiveOutputs& out, const AdaptiveShares& shares) {
    const Camera& camera = scene.camera();
    const int width = camera.width, height = camera.height;
    const Light& light = scene.light(lightIndex);
    const Tracer t{scene, lightIndex, light, trace, LightSampler(light), CameraRays(camera), settings.seed,
                     shares.kept};
    const size_t count = size_t(width) * size_t(height);
    std::vector<PixelState> state(count, PixelState::Outside);
    std::vector<SampleSums> sums(count);
    for (size_t i = 0; i < count; ++i) {
        const int x = int(i % size_t(width)), y = int(i / size_t(width));
        if (!pixels.select || pixels.select->at(x, y) != 0.0f) state[i] = PixelState::Selected;
        else if (pixels.growInto && pixels.growInto->at(x, y) != 0.0f) state[i] = PixelState::Reachable;
    }
    // The first round; false when the pixel sees no receiving surface.
    auto firstRound = [&](int x, int y, size_t i, SurfaceHit* hit) {
        if (!t.surface(x, y, hit)) {
            state[i] = PixelState::NoSurface;
            return false;
        }
        t.add(*hit, x, y, 0, uint32_t(sampling.minSamples), &sums[i]);
        // No weight in the first round decides the pixel only where the light cannot reach it: a
        // surface turned almost away from the light may see a sliver of it the round missed.
        const bool unlit = !(sums[i].weight > 0.0) && !lightReaches(light, hit->point, hit->normal);
        const bool decided = unlit || decidedByAgreement(sums[i], sampling);
        state[i] = decided ? PixelState::Decided : PixelState::Undecided;
        return true;
    };

    forEachRow(settings, height, "tracing shadow rays (first round)", 0.0f, 0.3f, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            SurfaceHit hit;
            if (state[i] == PixelState::Selected) firstRound(x, y, i, &hit);
        }
    });

    // The guard band: a decided (or not yet traced, reachable) pixel near one that disagrees takes
    // the further rounds too. Those that then disagree spread it on, wave after wave, so a faint
    // penumbra whose first rounds agree is followed to where further rounds see no occlusion.
    const int g = sampling.guardBand;
    auto spread = [&](const std::vector<size_t>& from, std::vector<size_t>* wave) {
        for (size_t f : from) {
            const int x = int(f % size_t(width)), y = int(f / size_t(width));
            for (int v = std::max(0, y - g); v <= std::min(height - 1, y + g); ++v)
                for (int u = std::max(0, x - g); u <= std::min(width - 1, x + g); ++u) {
                    const size_t i = size_t(v) * size_t(width) + size_t(u);
                    if (state[i] == PixelState::Decided) state[i] = PixelState::Undecided;
                    else if (state[i] == PixelState::Reachable) state[i] = PixelState::Promoted;
                    else continue;
                    wave->push_back(i);
                }
        }
    };
    std::vector<size_t> wave, disagreeing;
    for (size_t i = 0; i < count; ++i)
        if (state[i] == PixelState::Undecided) {
            wave.push_back(i);
            disagreeing.push_back(i);
        }
    spread(disagreeing, &wave);
    // The pixel target is set once, from the first wave: later waves add faint pixels whose
    // further rounds cost little error.
    size_t maskPixels = sampling.untracedMaskPixels;
    for (size_t i = 0; i < count; ++i)
        if ((state[i] == PixelState::Decided || state[i] == PixelState::Undecided) && sums[i].weight > 0.0) ++maskPixels;
    const float pixelTarget = pixelErrorTarget(sampling, maskPixels, wave.size());
    const int agreeingRays = raysToTrustAgreement(pixelTarget);

    // One pixel's outputs, once it is decided or finished.
    auto write = [&](size_t i) {
        const int x = int(i % size_t(width)), y = int(i / size_t(width));
        if (out.traced) out.traced->at(x, y) = 1.0f;
        if (out.rays) out.rays->at(x, y) = float(sums[i].rays);
        if (!(sums[i].weight > 0.0)) return;
        out.visibility->at(x, y) = float(sums[i].visible / sums[i].weight);
        if (out.mask) out.mask->at(x, y) = 1.0f;
    };
    // The further rounds of wave[begin, end), in chunks over the cores.
    auto traceWave = [&](const std::vector<size_t>& of, size_t begin, size_t end, const char* stage, float from,
                         float to) {
        const int chunks = int((end - begin + kWaveChunk - 1) / kWaveChunk);
        forEachRow(settings, chunks, stage, from, to, [&](int c) {
            for (size_t k = begin + size_t(c) * kWaveChunk; k < std::min(end, begin + size_t(c + 1) * kWaveChunk); ++k) {
                const size_t i = of[k];
                const int x = int(i % size_t(width)), y = int(i / size_t(width));
                SurfaceHit hit;
                // A reachable pixel has no first round yet; any other has its hit recomputed (the
                // same deterministic hit as its first round's).
                if (state[i] == PixelState::Promoted) {
                    if (!firstRound(x, y, i, &hit)) continue;
                } else {
                    t.surface(x, y, &hit);
                }
                continueRounds([&](uint32_t b, uint32_t e, SampleSums* into) { t.add(hit, x, y, b, e, into); },
                               sampling, pixelTarget, agreeingRays, &sums[i]);
                state[i] = PixelState::Finished;
            }
        });
    };
    const int shareCount = std::max(1, shares.count);

    for (int round = 0; !wave.empty(); ++round) {
        std::sort(wave.begin(), wave.end());
        if (round == 0 && shareCount > 1) {
            // The largest expected change first; within a share, in image order (the rays of
            // neighbours share the BVH's nodes).
            std::vector<float> change(count, 0.0f);
            for (size_t i : wave)
                if (state[i] != PixelState::Promoted && sums[i].weight > 0.0)
                    change[i] = std::abs(float(sums[i].visibility()) -
                                         out.visibility->at(int(i % size_t(width)), int(i / size_t(width))));
            std::stable_sort(wave.begin(), wave.end(), [&](size_t a, size_t b) { return change[a] > change[b]; });
            for (int s = 0; s < shareCount; ++s) {
                const size_t begin = wave.size() * size_t(s) / size_t(shareCount);
                const size_t end = wave.size() * size_t(s + 1) / size_t(shareCount);
                std::sort(wave.begin() + long(begin), wave.begin() + long(end));
                traceWave(wave, begin, end, "tracing shadow rays (adaptive rounds)",
                          0.3f + 0.65f * float(s) / float(shareCount), 0.3f + 0.65f * float(s + 1) / float(shareCount));
                if (s + 1 == shareCount || !shares.landed) continue;
                if (s == 0)
                    for (size_t i = 0; i < count; ++i)
                        if (state[i] == PixelState::Decided) write(i);
                for (size_t k = begin; k < end; ++k)
                    if (state[wave[k]] == PixelState::Finished) write(wave[k]);
                shares.landed(s + 1);
            }
        } else {
            traceWave(wave, 0, wave.size(),
                      round == 0 ? "tracing shadow rays (adaptive rounds)" : "tracing shadow rays (following the penumbra)",
                      round == 0 ? 0.3f : 0.95f, 0.95f);
        }
        disagreeing.clear();
        for (size_t i : wave)
            if (state[i] == PixelState::Finished && !sums[i].agree()) disagreeing.push_back(i);
        wave.clear();
        spread(disagreeing, &wave);
    }

    for (size_t i = 0; i < count; ++i)
        if (state[i] != PixelState::Outside && state[i] != PixelState::Reachable && state[i] != PixelState::NoSurface)
            write(i);
    settings.report(1.0f, "tracing shadow rays");
}

}  // namespace ss
