// How a GL method's uncertain pixels are re-traced: the penumbra plus a margin, adaptive rounds.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "renderer/refinement.h"

#include <algorithm>
#include <functional>

#include "core/error.h"
#include "reference/adaptive_sampling.h"
#include "reference/render_reference.h"

namespace ss {

namespace {

constexpr SettingSpec kRefineMargin =
    intSetting("refine_margin", 3, 0, 32, "pixels around the uncertain ones that are re-traced too");
constexpr SettingSpec kRefineSamples =
    intSetting("refine_samples", kReferenceAdaptiveDefaultSamples, 1, 1 << 16, "cap of samples per re-traced pixel");
constexpr SettingSpec kRefineVerify =
    intSetting("refine_verify", kRefineDefaultVerifyRays, 0, 1024,
               "rays that check each pixel the pass called certain (0: no check)");

}  // namespace

const SettingTable& refinementSettings() {
    static const SettingTable table =
        composed({kRefineMargin, kRefineSamples, kRefineVerify}, adaptiveSamplingSettings());
    return table;
}

namespace {

// 1 within `margin` pixels of a seed, inside the mask; 0 elsewhere.
Image growWithinMask(const Image& mask, int margin, const std::function<bool(int, int)>& seed) {
    const int width = mask.width, height = mask.height;
    Image out(width, height, 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (!seed(x, y)) continue;
            for (int j = std::max(0, y - margin); j <= std::min(height - 1, y + margin); ++j)
                for (int i = std::max(0, x - margin); i <= std::min(width - 1, x + margin); ++i)
                    if (mask.at(i, j) != 0.0f) out.at(i, j) = 1.0f;
        }
    return out;
}

}  // namespace

Image uncertainPixels(const Image& visibility, const Image& mask, int margin) {
    const int width = visibility.width, height = visibility.height;
    auto inMask = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < width && y < height && mask.at(x, y) != 0.0f;
    };
    // A pixel the pass cannot decide: V strictly between 0 and 1, or a certain V beside the
    // opposite certain V (a hard method's shadow edge).
    return growWithinMask(mask, margin, [&](int x, int y) {
        if (!inMask(x, y)) return false;
        const float v = visibility.at(x, y);
        if (v > 0.0f && v < 1.0f) return true;
        const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
        for (int k = 0; k < 4; ++k)
            if (inMask(x + dx[k], y + dy[k]) && visibility.at(x + dx[k], y + dy[k]) != v) return true;
        return false;
    });
}

namespace {

// The check of the pixels the pass called certain (inside the mask, outside the uncertain ones)
// with `verifyRays` rays each: V of the rays (the pass's V where none was traced) and the rays
// traced, per pixel, for rows [0, rowsDone). Each pixel's check is its own, so checking the rows
// in bands gives what checking them at once gives.
struct CertainCheck {
    Image certain, traced, rays;
    int rowsDone = 0;
};

CertainCheck certainPixels(const Image& visibility, const Image& mask, const Image& uncertain) {
    const int width = visibility.width, height = visibility.height;
    CertainCheck check{Image(width, height, 0.0f), visibility, Image(width, height, 0.0f)};
    for (size_t i = 0; i < check.certain.pixels.size(); ++i)
        check.certain.pixels[i] = mask.pixels[i] != 0.0f && uncertain.pixels[i] == 0.0f ? 1.0f : 0.0f;
    return check;
}

// Checks the certain pixels of rows [check->rowsDone, untilRow).
void checkCertainRows(const Scene& scene, int lightIndex, const RenderSettings& settings, const TraceScene& trace,
                      int verifyRays, int untilRow, CertainCheck* check) {
    if (untilRow <= check->rowsDone) return;
    const int width = check->certain.width;
    Image rows(width, check->certain.height, 0.0f);
    for (int y = check->rowsDone; y < untilRow; ++y)
        for (int x = 0; x < width; ++x) rows.at(x, y) = check->certain.at(x, y);
    AdaptiveSampling sampling;
    sampling.minSamples = sampling.maxSamples = verifyRays;
    sampling.guardBand = 0;
    traceAdaptive(scene, lightIndex, trace, sampling, settings, {&rows, nullptr},
                  {&check->traced, nullptr, &check->rays, nullptr});
    check->rowsDone = untilRow;
}

// Where the checked rows contradict the pass (a GL pass can be certain and wrong: a shadow map's
// missed caster, a faint penumbra it calls lit): V = 1 and a ray is blocked, or V = 0 and a ray
// sees the light; grown by `margin` pixels within the mask.
Image contradictedPixels(const CertainCheck& check, const Image& visibility, const Image& mask,
                         const Image& methodMask, int verifyRays, int margin) {
    const int width = visibility.width;
    auto checked = [&](int x, int y) { return y < check.rowsDone && check.certain.at(x, y) != 0.0f; };
    Image wrong = growWithinMask(mask, margin, [&](int x, int y) {
        if (!checked(x, y)) return false;
        const float gl = visibility.at(x, y), v = check.traced.at(x, y);
        return (gl == 1.0f && v < 1.0f) || (gl == 0.0f && v > 0.0f);
    });
    // Fewer than half the rays above the horizon (a surface turned almost away from the light):
    // too few to vouch for the pass, as for the adaptive rounds' agreement. Only inside the
    // method's mask: outside it such a pixel (the sky, a surface the light cannot reach) is what
    // the method said, V = 1.
    for (size_t i = 0; i < size_t(width) * size_t(check.rowsDone); ++i)
        if (check.certain.pixels[i] != 0.0f && methodMask.pixels[i] != 0.0f && 2.0f * check.rays.pixels[i] < float(verifyRays))
            wrong.pixels[i] = 1.0f;
    return wrong;
}

size_t maskPixelsOutside(const Image& mask, const Image& traced) {
    size_t n = 0;
    for (size_t i = 0; i < mask.pixels.size(); ++i) n += mask.pixels[i] != 0.0f && traced.pixels[i] == 0.0f;
    return n;
}

// What a refinement reads: the method's V (1 outside its mask) and mask, the pixels it was unsure
// of, and where the guard band may go.
struct RefineInput {
    const Scene& scene;
    const int lightIndex;
    const RenderSettings& settings;
    const TraceScene& trace;
    const int margin, verify;
    const AdaptiveSampling sampling;
    const Image &visibility, &mask, &uncertain, &everywhere, &growInto;
};

// The layers with V and mask replaced.
Layers withVisibility(const Layers& layers, const Image& visibility, const Image& mask) {
    Layers out;
    for (const auto& [name, image] : layers.items)
        out.add(name, name == "V" ? visibility : name == "mask" ? mask : image);
    return out;
}

// Rounds 1 .. rounds - 1 (refineUncertainPixels), on copies of the method's V and mask; `check`
// keeps the rows they checked and `kept` the samples they traced, for the last round.
void earlyRounds(const RefineInput& in, const Layers& layers, int rounds, CertainCheck* check, TracedSamples* kept,
                 const RefinementRoundFn& landed) {
    const int checkRounds = in.verify > 0 ? (rounds - 1) / 2 : 0, shareRounds = rounds - 1 - checkRounds;
    const int width = in.visibility.width, height = in.visibility.height;
    Image visibility = in.visibility, mask = in.mask, rays(width, height, 0.0f), refined(width, height, 0.0f);
    int round = 0;
    auto land = [&] {
        RefinementRound r{withVisibility(layers, visibility, mask), refined, in.sampling.errorTarget, ++round, rounds};
        if (in.settings.extraLayers) {
            Image all = check->rays;
            for (size_t i = 0; i < all.pixels.size(); ++i) all.pixels[i] += rays.pixels[i];
            r.layers.add("rays", std::move(all));
            r.layers.add("refined", refined);
        }
        landed(r);
    };
    auto traceInto = [&](const Image& select, const AdaptiveShares& shares) {
        AdaptiveSampling sampling = in.sampling;
        sampling.untracedMaskPixels = maskPixelsOutside(in.mask, select);
        traceAdaptive(in.scene, in.lightIndex, in.trace, sampling, in.settings, {&select, &in.growInto},
                      {&visibility, &mask, &rays, &refined}, shares);
    };
    traceInto(in.uncertain, {shareRounds, [&](int) { land(); }, kept});
    while (round < shareRounds) land();  // a first wave too small to share lands as it is
    Image selected = in.uncertain;
    for (int c = 1; c <= checkRounds; ++c) {
        checkCertainRows(in.scene, in.lightIndex, in.settings, in.trace, in.verify, height * c / checkRounds, check);
        const Image wrong = contradictedPixels(*check, in.visibility, in.everywhere, in.mask, in.verify, in.margin);
        Image fresh(width, height, 0.0f);
        bool any = false;
        for (size_t i = 0; i < fresh.pixels.size(); ++i)
            if (wrong.pixels[i] != 0.0f && selected.pixels[i] == 0.0f) {
                fresh.pixels[i] = selected.pixels[i] = 1.0f;
                any = true;
            }
        if (any) traceInto(fresh, {1, {}, kept});
        land();
    }
}

}  // namespace

Refinement refineUncertainPixels(const Scene& scene, int lightIndex, const RenderSettings& settings,
                                 TraceSceneCache& cache, Layers& layers, const RefinementRoundFn& landed) {
    const int margin = settings.integer(kRefineMargin);
    const int samples = settings.integer(kRefineSamples);
    const int verify = settings.integer(kRefineVerify);
    const int rounds = settings.refineRounds;
    Image *visibility = nullptr, *mask = nullptr;
    for (auto& [name, image] : layers.items) {
        if (name == "V") visibility = &image;
        if (name == "mask") mask = &image;
    }
    if (!visibility || !mask) fail(SS_ERROR_INTERNAL, "refine: the method made no V or mask layer");
    const Image uncertain = uncertainPixels(*visibility, *mask, margin);

    settings.report(0.0f, "building the ray-tracing scene");
    std::shared_ptr<const TraceScene> trace = cache.get(scene, lightIndex);
    const int width = visibility->width, height = visibility->height;
    // The check covers every pixel, not only the method's mask: outside it the method said V = 1
    // (sweep shades its receiver plane only, leaving the casters and other receivers lit), and
    // that is what a composite multiplies there too.
    const Image everywhere(width, height, 1.0f);
    for (size_t i = 0; i < mask->pixels.size(); ++i)
        if (mask->pixels[i] == 0.0f) visibility->pixels[i] = 1.0f;
    // The guard band reads it before the last round writes the mask.
    const Image growInto = verify > 0 ? everywhere : *mask;
    CertainCheck check = certainPixels(*visibility, everywhere, uncertain);
    std::unique_ptr<TracedSamples> kept;
    if (landed && rounds > 1) {
        kept = std::make_unique<TracedSamples>(size_t(width) * size_t(height));
        const RefineInput in{scene,     lightIndex, settings, *trace,    margin,     verify,
                             adaptiveSampling(settings, samples), *visibility, *mask, uncertain, everywhere, growInto};
        earlyRounds(in, layers, rounds, &check, kept.get(), landed);
    }

    // The last round: what one round gives.
    Image select = uncertain;
    if (verify > 0) {
        checkCertainRows(scene, lightIndex, settings, *trace, verify, height, &check);
        const Image wrong = contradictedPixels(check, *visibility, everywhere, *mask, verify, margin);
        for (size_t i = 0; i < select.pixels.size(); ++i) select.pixels[i] = std::max(select.pixels[i], wrong.pixels[i]);
    }
    AdaptiveSampling sampling = adaptiveSampling(settings, samples);
    sampling.untracedMaskPixels = maskPixelsOutside(*mask, select);
    // A traced pixel the light reaches joins the mask: its V is the ray tracer's now.
    Image tracedRays(width, height, 0.0f), refined(width, height, 0.0f);
    traceAdaptive(scene, lightIndex, *trace, sampling, settings, {&select, &growInto},
                  {visibility, mask, &tracedRays, &refined}, {1, {}, kept.get()});
    Refinement out{refined, sampling.errorTarget};
    if (settings.extraLayers) {
        for (size_t i = 0; i < check.rays.pixels.size(); ++i) check.rays.pixels[i] += tracedRays.pixels[i];
        layers.add("rays", std::move(check.rays));
        layers.add("refined", std::move(refined));
    }
    return out;
}

}  // namespace ss
