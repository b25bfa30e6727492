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

Image wronglyCertainPixels(const Scene& scene, int lightIndex, const RenderSettings& settings,
                           const TraceScene& trace, int verifyRays, const Image& visibility,
                           const Image& mask, const Image& methodMask, const Image& uncertain, int margin,
                           Image* rays) {
    const int width = visibility.width, height = visibility.height;
    Image certain(width, height, 0.0f);
    for (size_t i = 0; i < certain.pixels.size(); ++i)
        certain.pixels[i] = mask.pixels[i] != 0.0f && uncertain.pixels[i] == 0.0f ? 1.0f : 0.0f;
    AdaptiveSampling check;
    check.minSamples = check.maxSamples = verifyRays;
    check.guardBand = 0;
    Image traced = visibility, checkRays(width, height, 0.0f);
    traceAdaptive(scene, lightIndex, trace, check, settings, {&certain, nullptr}, {&traced, nullptr, &checkRays, nullptr});
    for (size_t i = 0; i < rays->pixels.size(); ++i) rays->pixels[i] += checkRays.pixels[i];
    Image wrong = growWithinMask(mask, margin, [&](int x, int y) {
        if (certain.at(x, y) == 0.0f) return false;
        const float gl = visibility.at(x, y), v = traced.at(x, y);
        return (gl == 1.0f && v < 1.0f) || (gl == 0.0f && v > 0.0f);
    });
    // Fewer than half the rays above the horizon (a surface turned almost away from the light):
    // too few to vouch for the pass, as for the adaptive rounds' agreement. Only inside the
    // method's mask: outside it such a pixel (the sky, a surface the light cannot reach) is what
    // the method said, V = 1.
    for (size_t i = 0; i < wrong.pixels.size(); ++i)
        if (certain.pixels[i] != 0.0f && methodMask.pixels[i] != 0.0f && 2.0f * checkRays.pixels[i] < float(verifyRays))
            wrong.pixels[i] = 1.0f;
    return wrong;
}

Refinement refineUncertainPixels(const Scene& scene, int lightIndex, const RenderSettings& settings,
                                 TraceSceneCache& cache, Layers& layers, const RefinementRoundFn& landed) {
    const int margin = settings.integer(kRefineMargin);
    const int samples = settings.integer(kRefineSamples);
    const int verify = settings.integer(kRefineVerify);
    AdaptiveShares shares;
    shares.count = settings.refineRounds;
    AdaptiveSampling sampling = adaptiveSampling(settings, samples);
    Image *visibility = nullptr, *mask = nullptr;
    for (auto& [name, image] : layers.items) {
        if (name == "V") visibility = &image;
        if (name == "mask") mask = &image;
    }
    if (!visibility || !mask) fail(SS_ERROR_INTERNAL, "refine: the method made no V or mask layer");
    Image select = uncertainPixels(*visibility, *mask, margin);

    settings.report(0.0f, "building the ray-tracing scene");
    std::shared_ptr<const TraceScene> trace = cache.get(scene, lightIndex);
    const int width = visibility->width, height = visibility->height;
    // The check covers every pixel, not only the method's mask: outside it the method said V = 1
    // (sweep shades its receiver plane only, leaving the casters and other receivers lit), and
    // that is what a composite multiplies there too.
    const Image everywhere(width, height, 1.0f);
    for (size_t i = 0; i < mask->pixels.size(); ++i)
        if (mask->pixels[i] == 0.0f) visibility->pixels[i] = 1.0f;
    Image rays(width, height, 0.0f);
    if (verify > 0) {
        const Image wrong = wronglyCertainPixels(scene, lightIndex, settings, *trace, verify, *visibility, everywhere,
                                                 *mask, select, margin, &rays);
        for (size_t i = 0; i < select.pixels.size(); ++i) select.pixels[i] = std::max(select.pixels[i], wrong.pixels[i]);
    }
    for (size_t i = 0; i < mask->pixels.size(); ++i)
        if (mask->pixels[i] != 0.0f && select.pixels[i] == 0.0f) ++sampling.untracedMaskPixels;

    // A traced pixel the light reaches joins the mask: its V is the ray tracer's now.
    Image tracedRays(width, height, 0.0f), refined(width, height, 0.0f);
    auto withTraceLayers = [&](Layers& into, Image checked) {
        for (size_t i = 0; i < checked.pixels.size(); ++i) checked.pixels[i] += tracedRays.pixels[i];
        into.add("rays", std::move(checked));
        into.add("refined", refined);
    };
    if (landed)
        shares.landed = [&](int share) {
            RefinementRound round{layers, refined, sampling.errorTarget, share, shares.count};
            if (settings.extraLayers) withTraceLayers(round.layers, rays);
            landed(round);
        };
    traceAdaptive(scene, lightIndex, *trace, sampling, settings, {&select, verify > 0 ? &everywhere : mask},
                  {visibility, mask, &tracedRays, &refined}, shares);
    Refinement out{refined, sampling.errorTarget};
    if (settings.extraLayers) withTraceLayers(layers, std::move(rays));
    return out;
}

}  // namespace ss
