// Checks the reference's adaptive sampling: error against 4096 samples, rays saved, determinism, settings.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/scene.h"
#include "reference/adaptive_sampling.h"
#include "reference/render_reference.h"
#include "reference/trace_scene_cache.h"
#include "renderer/renderer.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::layer;

RenderSettings fixedSamples(int samples) {
    RenderSettings s;
    s.samples = samples;
    return s;
}

RenderSettings adaptiveSettings(const std::string& errorTarget) {
    RenderSettings s;
    s.options = {{"adaptive", "on"}, {"error_target", errorTarget}};
    return s;
}

test::SceneParams smallScene() {
    test::SceneParams p;
    p.width = 96;
    p.height = 72;
    return p;
}

struct Comparison {
    double rmse = 0.0, maxAbs = 0.0;
    int maskPixels = 0, maskDiffers = 0;
};

Comparison compare(const Layers& a, const Layers& truth) {
    const Image &va = layer(a, "V"), &vt = layer(truth, "V"), &ma = layer(a, "mask"),
                &mt = layer(truth, "mask");
    Comparison c;
    double sum = 0.0;
    for (size_t i = 0; i < va.pixels.size(); ++i) {
        if (ma.pixels[i] != mt.pixels[i]) ++c.maskDiffers;
        if (mt.pixels[i] == 0.0f) continue;
        const double d = double(va.pixels[i]) - double(vt.pixels[i]);
        sum += d * d;
        c.maxAbs = std::max(c.maxAbs, std::abs(d));
        ++c.maskPixels;
    }
    c.rmse = c.maskPixels ? std::sqrt(sum / c.maskPixels) : 0.0;
    return c;
}

double total(const Image& img) {
    double s = 0.0;
    for (float v : img.pixels) s += v;
    return s;
}

TEST(ReferenceAdaptive, WithinItsErrorTargetOfA4096SampleReference) {
    test::SceneParams p;
    p.width = 64;
    p.height = 48;
    for (test::NamedScene& named : test::sharedScenes(p)) {
        TraceSceneCache cache;
        const Layers truth = renderReference(named.scene, 0, fixedSamples(4096), &cache);
        for (const char* target : {"0.005", "0.02"}) {
            const Layers adaptive = renderReference(named.scene, 0, adaptiveSettings(target), &cache);
            const Comparison c = compare(adaptive, truth);
            std::printf("%s target %s: RMSE %.5f, max %.4f over %d pixels, %.1f rays per pixel\n",
                        named.name.c_str(), target, c.rmse, c.maxAbs, c.maskPixels,
                        total(layer(adaptive, "rays")) / c.maskPixels);
            EXPECT_EQ(c.maskDiffers, 0) << named.name;
            EXPECT_GT(c.maskPixels, 2000) << named.name;
            EXPECT_LE(c.rmse, std::stod(target)) << named.name << " at error_target " << target;
        }
    }
}

TEST(ReferenceAdaptive, TracesFarFewerRaysWhereMostPixelsAreLitOrInUmbra) {
    // A small light: a thin penumbra around a wide umbra, lit ground elsewhere.
    test::SceneParams p = smallScene();
    p.lightDiameter = 0.3f;
    Scene scene = test::sceneBox(p);
    TraceSceneCache cache;
    const Layers truth = renderReference(scene, 0, fixedSamples(4096), &cache);
    const Layers adaptive = renderReference(scene, 0, adaptiveSettings("0.005"), &cache);
    const Image& rays = layer(adaptive, "rays");
    const Comparison c = compare(adaptive, truth);
    const double perPixel = total(rays) / c.maskPixels;
    std::printf("box, light 0.3: %.1f rays per pixel (fixed count 256; cap 1024), RMSE %.5f\n",
                perPixel, c.rmse);
    EXPECT_LE(c.rmse, 0.005);
    EXPECT_LT(perPixel, 256.0 / 4.0);
    // A lit pixel in the corner, far from the shadow, is decided by the first round.
    EXPECT_EQ(rays.at(2, 2), 16.0f);
    EXPECT_EQ(layer(adaptive, "V").at(2, 2), 1.0f);
    // Pixels at the shadow's edge took further rounds; with a tight target some needed more than
    // the fixed count, and none more than the cap.
    auto most = [](const Image& r) { return *std::max_element(r.pixels.begin(), r.pixels.end()); };
    EXPECT_GT(most(rays), 32.0f);
    const Layers tight = renderReference(scene, 0, adaptiveSettings("0.0005"), &cache);
    EXPECT_GT(most(layer(tight, "rays")), 256.0f);
    EXPECT_LE(most(layer(tight, "rays")), 1024.0f);
    EXPECT_LE(compare(tight, truth).rmse, c.rmse);
}

// An occluder far smaller than the light: no umbra, a wide faint penumbra (V >= 0.97) whose
// first rounds mostly agree. The guard band follows it outwards, wave after wave, so the shadow
// is traced to where further rounds see no occlusion.
TEST(ReferenceAdaptive, TracesTheFaintPenumbraOfAnOccluderSmallerThanTheLight) {
    test::SceneParams p = smallScene();
    p.lightDiameter = 3.0f;
    p.lightHeight = 3.0f;
    p.cameraZoom = 2.0f;
    Scene scene;
    scene.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addMesh(test::makeUvSphere({0.0f, 0.0f, 1.2f}, 0.12f, 12, 24, SS_MESH_CAST));
    scene.addLight(test::makeDiskLight({0.0f, 0.0f, p.lightHeight}, p.lightDiameter));
    scene.setCamera(test::sceneBox(p).camera());  // the shared camera, zoomed in on the shadow
    TraceSceneCache cache;
    const Layers truth = renderReference(scene, 0, fixedSamples(4096), &cache);
    const Layers adaptive = renderReference(scene, 0, adaptiveSettings("0.005"), &cache);
    const Comparison c = compare(adaptive, truth);
    // The shadow, in pixels: sum of 1 - V over the mask.
    auto shadow = [](const Layers& l) {
        const Image &v = layer(l, "V"), &m = layer(l, "mask");
        double s = 0.0;
        for (size_t i = 0; i < v.pixels.size(); ++i)
            if (m.pixels[i] != 0.0f) s += 1.0 - v.pixels[i];
        return s;
    };
    // Pixels in the truth's shadow (V < 0.995) that the adaptive run left fully lit.
    int shadowed = 0, leftLit = 0;
    for (size_t i = 0; i < layer(truth, "V").pixels.size(); ++i) {
        if (layer(truth, "mask").pixels[i] == 0.0f || layer(truth, "V").pixels[i] >= 0.995f) continue;
        ++shadowed;
        leftLit += layer(adaptive, "V").pixels[i] == 1.0f;
    }
    std::printf("small occluder: RMSE %.5f, shadow %.1f of the truth's %.1f pixels, %d of %d shadowed pixels left lit, %.1f rays per pixel\n",
                c.rmse, shadow(adaptive), shadow(truth), leftLit, shadowed, total(layer(adaptive, "rays")) / c.maskPixels);
    EXPECT_EQ(c.maskDiffers, 0);
    EXPECT_GT(shadowed, 500);
    EXPECT_LE(c.rmse, 0.005);
    EXPECT_GE(shadow(adaptive), 0.9 * shadow(truth));
    EXPECT_LE(leftLit, shadowed / 10);
}

// The target is what the rounds aim at, not a bound they keep far from: where the penumbra is a
// fair share of the mask (so neither the first round's 16 rays nor kMaxPixelError set the error),
// the mask's RMSE comes within about a factor of 2.5 below the target (kPenumbraShare holds a
// penumbra below a quarter of the mask a little lower).
TEST(ReferenceAdaptive, TheMasksErrorComesCloseToItsTargetWithoutPassingIt) {
    test::SceneParams p;
    p.width = 128;
    p.height = 96;
    for (test::NamedScene& named : test::sharedScenes(p)) {
        if (named.name != "torus" && named.name != "overlapping") continue;
        TraceSceneCache cache;
        const Layers truth = renderReference(named.scene, 0, fixedSamples(4096), &cache);
        const Comparison c = compare(renderReference(named.scene, 0, adaptiveSettings("0.005"), &cache), truth);
        std::printf("%s at 128x96, target 0.005: RMSE %.5f (%.2f of the target)\n", named.name.c_str(), c.rmse,
                    c.rmse / 0.005);
        EXPECT_LE(c.rmse, 0.005) << named.name;
        EXPECT_GE(c.rmse, 0.35 * 0.005) << named.name;
    }
}

// A wall that sees only a sliver of the light above its horizon: a first round of 16 samples
// often finds none there, yet the light reaches the wall (E_L > 0, as the 4096-sample truth
// finds): such a pixel is not decided by its empty first round.
TEST(ReferenceAdaptive, APixelTheLightReachesIsNotDecidedByAnEmptyFirstRound) {
    Scene scene;
    scene.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    // The wall's face at x = 1.4 faces the camera (-x); the light spans x in [1.3, 4.3].
    scene.addMesh(test::makeBox({1.4f, -1.5f, 0.0f}, {1.6f, 1.5f, 1.6f}, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addLight(test::makeDiskLight({2.8f, 0.0f, 2.0f}, 3.0f));
    scene.setCamera(makeLookAtCamera({-2.0f, 0.0f, 1.0f}, {1.4f, 0.0f, 0.8f}, {0.0f, 0.0f, 1.0f},
                                     glm::radians(40.0f), 96, 72, 0.1f, 50.0f));
    TraceSceneCache cache;
    const Layers truth = renderReference(scene, 0, fixedSamples(4096), &cache);
    const Layers adaptive = renderReference(scene, 0, adaptiveSettings("0.005"), &cache);
    const Comparison c = compare(adaptive, truth);
    std::printf("sliver of light: %d of %d mask pixels outside the adaptive mask, RMSE %.5f\n", c.maskDiffers,
                c.maskPixels, c.rmse);
    EXPECT_GT(c.maskPixels, 2000);
    EXPECT_LE(c.maskDiffers, c.maskPixels / 1000);
    EXPECT_LE(c.rmse, 0.005);
}

// The target is the mask's RMSE: the undecided pixels share it, each allowed more error the
// fewer they are, within [target, kPenumbraShare x target] and at most kMaxPixelError.
TEST(ReferenceAdaptive, ThePixelTargetSpreadsTheMasksErrorOverTheUndecidedPixels) {
    AdaptiveSampling a;
    a.errorTarget = 0.005f;
    EXPECT_FLOAT_EQ(pixelErrorTarget(a, 1000, 1000), 0.005f);
    EXPECT_FLOAT_EQ(pixelErrorTarget(a, 1000, 640), 0.00625f);
    EXPECT_FLOAT_EQ(pixelErrorTarget(a, 1000, 250), 0.01f);
    // A small penumbra keeps at most twice the image's error.
    EXPECT_FLOAT_EQ(pixelErrorTarget(a, 1000000, 1), AdaptiveSampling::kPenumbraShare * 0.005f);
    EXPECT_FLOAT_EQ(pixelErrorTarget(a, 1000, 0), 0.005f);
    a.errorTarget = 0.04f;
    EXPECT_FLOAT_EQ(pixelErrorTarget(a, 1000, 10), AdaptiveSampling::kMaxPixelError);
    a.errorTarget = 0.2f;
    EXPECT_FLOAT_EQ(pixelErrorTarget(a, 1000, 10), 0.2f);
}

// Beside a disagreeing pixel, agreement is trusted only after 2 / (e * target) rays.
TEST(ReferenceAdaptive, AgreementBesideADisagreeingPixelNeedsRaysInProportionToTheTarget) {
    EXPECT_EQ(raysToTrustAgreement(0.005f), 148);
    EXPECT_EQ(raysToTrustAgreement(0.02f), 37);
    EXPECT_EQ(raysToTrustAgreement(AdaptiveSampling::kMaxPixelError), 15);
}

TEST(ReferenceAdaptive, DeterministicForASeedWhateverTheThreadCount) {
    Scene scene = test::sceneTorus(smallScene());
    RenderSettings one = adaptiveSettings("0.01"), two = one, other = one;
    one.options["threads"] = "1";
    two.options["threads"] = "2";
    other.seed = 7;
    const Layers a = renderReference(scene, 0, one), b = renderReference(scene, 0, two),
                 c = renderReference(scene, 0, other);
    EXPECT_EQ(layer(a, "V").pixels, layer(b, "V").pixels);
    EXPECT_EQ(layer(a, "rays").pixels, layer(b, "rays").pixels);
    EXPECT_NE(layer(a, "V").pixels, layer(c, "V").pixels);
}

// Samples kept by one call (TracedSamples) give a later call what tracing them again gives, bit for
// bit, even under another error target (other stopping points) and over more pixels; the kept
// blocks are the pixels' own, in their order.
TEST(ReferenceAdaptive, KeptSamplesGiveALaterCallWhatTracingGives) {
    Scene scene = test::sceneTorus(smallScene());
    const Camera& camera = scene.camera();
    TraceSceneCache cache;
    const std::shared_ptr<const TraceScene> trace = cache.get(scene, 0);
    RenderSettings settings;
    Image left(camera.width, camera.height, 0.0f);
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width / 2; ++x) left.at(x, y) = 1.0f;
    struct Traced {
        Image v, rays;
    };
    auto traceWith = [&](float target, const Image* select, TracedSamples* kept) {
        AdaptiveSampling sampling;
        sampling.errorTarget = target;
        Traced out{Image(camera.width, camera.height, 1.0f), Image(camera.width, camera.height, 0.0f)};
        traceAdaptive(scene, 0, *trace, sampling, settings, {select, nullptr}, {&out.v, nullptr, &out.rays, nullptr},
                      {1, {}, kept});
        return out;
    };
    TracedSamples kept(size_t(camera.width) * size_t(camera.height));
    traceWith(0.03f, &left, &kept);  // a looser target over half the image
    const Traced fresh = traceWith(0.01f, nullptr, nullptr), again = traceWith(0.01f, nullptr, &kept);
    EXPECT_EQ(again.v.pixels, fresh.v.pixels);
    EXPECT_EQ(again.rays.pixels, fresh.rays.pixels);
    double sumRays = 0.0;
    for (float r : fresh.rays.pixels) sumRays += r;
    EXPECT_GT(sumRays, 16.0 * double(camera.width * camera.height)) << "further rounds were traced";
    // A pixel's first round is kept; a block after sums it did not follow is not given.
    size_t pixel = 0;
    while (pixel < fresh.rays.pixels.size() && !(left.pixels[pixel] != 0.0f && fresh.rays.pixels[pixel] > 16.0f)) ++pixel;
    ASSERT_LT(pixel, fresh.rays.pixels.size()) << "no pixel of the left half took further rounds";
    SampleSums first;
    ASSERT_TRUE(kept.take(pixel, 0, 16, &first));
    EXPECT_GT(first.rays, 0);
    SampleSums next = first;
    EXPECT_TRUE(kept.take(pixel, 16, 32, &next));
    EXPECT_GT(next.rays, first.rays);
    SampleSums other = first;
    other.visible += 0.5;
    EXPECT_FALSE(kept.take(pixel, 16, 32, &other));
    EXPECT_FALSE(kept.take(pixel, 0, 32, &first));
}

TEST(ReferenceAdaptive, SettingsAreReadByNameAndRefusedOutOfRange) {
    Scene scene = test::sceneBox(smallScene());
    Renderer renderer(SS_BACKEND_AUTO);
    auto statusWith = [&](const std::string& key, const std::string& value) {
        RenderSettings s = adaptiveSettings("0.01");
        s.options[key] = value;
        return test::statusOf([&] { renderer.render(scene, 0, "reference", s, nullptr); });
    };
    EXPECT_EQ(statusWith("error_target", "0"), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(statusWith("guard_band", "-1"), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(statusWith("adaptive", "maybe"), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(statusWith("guard_band", "1"), SS_OK);
    // Without "adaptive" the fixed count runs and there is no "rays" layer.
    const Layers fixed = renderReference(scene, 0, fixedSamples(16));
    EXPECT_EQ(fixed.find("rays"), nullptr);
}

}  // namespace
}  // namespace ss
