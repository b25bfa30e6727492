// How the reference spends its light samples where they matter: rounds per pixel, stopped when decided.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "core/settings.h"
#include "reference/light_sampler.h"
#include "reference/sample_sequence.h"
#include "reference/trace_scene.h"
#include "reference/visibility_estimator.h"

namespace ss {

// Per pixel, light samples (the same Owen-scrambled Sobol points as the fixed count) in rounds
// of doubling size: `minSamples` first, then 2x, 4x, ... up to `maxSamples`.
// - A pixel whose first round agrees (all blocked or all visible, at least minSamples / 2 rays
//   above the horizon) or carries no weight where the light cannot reach it (lightReaches) is
//   decided, unless a pixel
//   within `guardBand` pixels disagrees: thin casters and shadow edges hide between samples.
//   A pixel the band took in that disagrees after its further rounds takes in its own
//   neighbours, in waves, so the band follows a faint penumbra outwards.
// - Every other pixel stops when its estimated error is at most the pixel target and the round
//   before was on track for it (kOnTrack), or at `maxSamples`; one passing round suffices while
//   every sample so far agrees, once the pixel has traced enough rays to trust the agreement
//   (raysToTrustAgreement). Rounds count only once the pixel has traced minSamples / 2 rays. The estimate of a round is half
//   the difference between V of the samples before it and V of the round's own samples (each a
//   power-of-two prefix or block of a (0,2)-sequence, so both are stratified estimates).
// - `errorTarget` is the RMSE over the mask the rounds aim at: decided pixels are exact, so the
//   u undecided pixels of m mask pixels may each err by errorTarget * sqrt(m / u), at most
//   kPenumbraShare times errorTarget and kMaxPixelError (and never less than errorTarget).
struct AdaptiveSampling {
    static constexpr float kMaxPixelError = 0.05f;
    // A small penumbra on a large lit receiver would otherwise take the whole mask's budget
    // (small_occluder: 3.5x the target per pixel) and show as noise where the eye looks: the
    // penumbra keeps at most twice the image's error.
    static constexpr float kPenumbraShare = 2.0f;
    // A round's estimate is of twice the samples of the round before it, and a stratified
    // estimate's error falls about as N^-0.75: the round before is on track for the pixel target
    // when its estimate is at most 2^0.75 times it.
    static constexpr double kOnTrack = 1.6817928305074290;
    int minSamples = 16;
    int maxSamples = 1024;
    float errorTarget = 0.01f;
    int guardBand = 2;
    // Mask pixels the caller keeps without tracing (refine: where the GL pass was certain);
    // they count in m above.
    size_t untracedMaskPixels = 0;
};

// The error each undecided pixel may keep so that the mask's RMSE meets the target.
float pixelErrorTarget(const AdaptiveSampling& sampling, size_t maskPixels, size_t undecidedPixels);

// Rays a pixel beside a disagreeing one must trace before agreement alone stops it: a share p
// of the light blocked (or seen) hides from n stratified rays with probability about (1 - p)^n,
// an RMS error sqrt(p^2 (1 - p)^n) <= 2 / (e n) at worst (p = 2 / n); this keeps it within
// `pixelTarget`.
int raysToTrustAgreement(float pixelTarget);

// One point on its own, without the guard band (no neighbours to consult: the sparse check's
// isolated pixels): the first round, then further rounds unless the first agrees. Adds to *sums.
void sampleAdaptively(const TraceScene& trace, const LightSampler& sampler, const SurfaceHit& hit,
                      const SampleSequence& sequence, bool castShadows, const AdaptiveSampling& sampling,
                      SampleSums* sums);

// The settings the adaptive sampling reads ("error_target", "guard_band"); `maxSamples` is the
// render's sample count.
const SettingTable& adaptiveSamplingSettings();
AdaptiveSampling adaptiveSampling(const RenderSettings& settings, int maxSamples);

// Which pixels traceAdaptive traces: those where `select` is non-zero (every pixel when null),
// and those where `growInto` is non-zero that the guard band reaches (none when null).
struct AdaptivePixels {
    const Image* select = nullptr;
    const Image* growInto = nullptr;
};
// Where traceAdaptive writes, per traced pixel: V into *visibility and 1 into *mask where the
// light reaches the surface (E_L > 0); the shadow rays it traced into *rays; 1 into *traced.
// Untraced pixels keep their values. Any but visibility may be null.
struct AdaptiveOutputs {
    Image* visibility = nullptr;
    Image* mask = nullptr;
    Image* rays = nullptr;
    Image* traced = nullptr;
};

// The sums of the blocks of samples traceAdaptive traced per pixel, kept for later calls over
// the same scene, light, camera, seed and sample counts: a block a pixel traced before, after the
// same blocks before it, is taken from here instead of traced again, bit for bit what tracing
// gives. So a call's result costs only what earlier calls (a preview's rounds, refinement.h)
// left out. About 40 bytes a block kept (one per doubling round of a traced pixel).
class TracedSamples {
public:
    explicit TracedSamples(size_t pixels) : blocks_(pixels) {}
    // *sums after the kept block [begin, end) of `pixel` whose blocks before it left *sums as it
    // is; false when no such block is kept.
    bool take(size_t pixel, uint32_t begin, uint32_t end, SampleSums* sums) const;
    // The sums after block [begin, end) of `pixel`. A pixel's blocks are kept by the thread
    // tracing that pixel only.
    void keep(size_t pixel, uint32_t begin, uint32_t end, const SampleSums& after);

private:
    struct Block {
        uint32_t begin, end;
        SampleSums after;
    };
    std::vector<std::unique_ptr<std::vector<Block>>> blocks_;
};

// The first wave of further rounds (the pixels the first round left undecided and their guard
// band) traced in `count` shares of equal size, the largest expected change first: the first
// round's V against what *visibility held (the guard band's pixels without a first round last).
// After each share but the last, the outputs hold every pixel decided or finished so far (the
// others as they were) and `landed(share)` runs (1-based), on the caller's thread. Every pixel
// ends as in one go: the last share's outputs are those of count = 1.
// `kept` (may be null): the samples are taken from and added to it.
struct AdaptiveShares {
    int count = 1;
    std::function<void(int share)> landed;
    TracedSamples* kept = nullptr;
};

// Traces `pixels` of the scene's camera for light `lightIndex` in adaptive rounds. The guard band
// follows the penumbra: a pixel the band promoted that disagrees after its further rounds
// promotes its own neighbours within the band, wave after wave until no pixel is promoted.
// Deterministic for settings.seed and independent of the thread count and of shares.count.
void traceAdaptive(const Scene& scene, int lightIndex, const TraceScene& trace,
                   const AdaptiveSampling& sampling, const RenderSettings& settings,
                   const AdaptivePixels& pixels, const AdaptiveOutputs& out, const AdaptiveShares& shares = {});

}  // namespace ss
