// Checks refinement (RenderSettings::refine): untouched where the pass is certain, closer to the truth
// elsewhere. SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "io/metrics.h"
#include "reference/trace_scene_cache.h"
#include "renderer/refinement.h"
#include "test_layers.h"
#include "test_pcss_support.h"

namespace ss {
namespace {

using test::layer;

test::SceneParams smallSoftScene() {
    test::SceneParams p = test::softSceneParams();
    p.width = 96;
    p.height = 72;
    return p;
}

// Where the pass is certain and the verification's rays agree with it, V is the GL value to the
// bit; the uncertain pixels and their margin are all traced.
TEST(Refinement, IdenticalToTheGlResultWhereThePassIsCertain) {
    Scene scene = test::sceneBox(smallSoftScene());
    for (const char* method : {"pcss", "shadow_map", "penumbra_map"}) {
        const Layers gl = test::renderWith(scene, method);
        const Layers refined = test::refinedWith(scene, method);
        const Image &vGl = layer(gl, "V"), &vRef = layer(refined, "V"), &traced = layer(refined, "refined"),
                    &rays = layer(refined, "rays"), &mask = layer(gl, "mask");
        const Image uncertain = uncertainPixels(vGl, mask, 3);
        int certain = 0, changed = 0, grown = 0;
        for (size_t i = 0; i < vGl.pixels.size(); ++i) {
            if (uncertain.pixels[i] != 0.0f) EXPECT_EQ(traced.pixels[i], 1.0f) << method << " pixel " << i;
            else grown += traced.pixels[i] != 0.0f;
            if (traced.pixels[i] == 0.0f) {
                ++certain;
                EXPECT_EQ(vRef.pixels[i], vGl.pixels[i]) << method << " pixel " << i;
                // Only the verification's rays: 8 per mask pixel the light reaches above the horizon.
                EXPECT_LE(rays.pixels[i], float(kRefineDefaultVerifyRays)) << method << " pixel " << i;
                if (mask.pixels[i] == 0.0f) {
                    EXPECT_EQ(rays.pixels[i], 0.0f) << method << " pixel " << i;
                }
            } else if (vRef.pixels[i] != vGl.pixels[i]) {
                ++changed;
            }
        }
        std::printf("%s: %d certain pixels kept, %d traced beyond the uncertain ones\n", method, certain, grown);
        EXPECT_GT(certain, int(vGl.pixels.size() / 2)) << method;
        EXPECT_GT(changed, 0) << method;
        // The method's own layers stay, mask included, in their order; refinement adds two.
        EXPECT_EQ(layer(refined, "mask").pixels, layer(gl, "mask").pixels) << method;
        ASSERT_EQ(refined.items.size(), gl.items.size() + 2) << method;
        size_t k = 0;
        for (const auto& [name, image] : gl.items) {
            if (name == "umbra" || name == "penumbra") continue;
            while (refined.items[k].first != name) ++k;
            if (name != "V") {
                EXPECT_EQ(refined.items[k].second.pixels, image.pixels) << method << " " << name;
            }
        }
    }
}

TEST(Refinement, CloserToA4096SampleReferenceThanTheGlMethodAlone) {
    Scene scene = test::sceneBox(smallSoftScene());
    const Layers truth = test::renderWith(scene, "reference", {}, 4096);
    for (const char* method : {"pcss", "shadow_map"}) {
        const Layers gl = test::renderWith(scene, method);
        const Layers refined = test::refinedWith(scene, method);
        const Metrics a = test::compareToReference(gl, truth), b = test::compareToReference(refined, truth);
        double traced = 0.0;
        for (float v : layer(refined, "refined").pixels) traced += v;
        std::printf("%s: RMSE %.4f alone, %.4f refined (%.0f%% of pixels traced)\n", method, a.rmse,
                    b.rmse, 100.0 * traced / double(layer(gl, "V").pixels.size()));
        EXPECT_LT(b.rmse, a.rmse) << method;
        EXPECT_LT(b.rmse, 0.5 * a.rmse) << method;
    }
}

// A refined result's estimate: the check where the GL pass was kept, the error target where the
// rounds traced. It bounds the measured error from above, by no more than the target, at two
// targets (the check's own rays, scored against the refined V, had made it several times the
// error where much of the image is traced).
TEST(Refinement, TheEstimateOfARefinedResultBoundsItsErrorWithinTheTarget) {
    Scene scene = test::sceneBox(smallSoftScene());
    const Layers truth = test::renderWith(scene, "reference", {}, 4096);
    for (const char* target : {"0.005", "0.01"}) {
        RenderSettings s;
        s.options = {{"error_target", target}, {"estimate_rmse", "1"}};
        s.refine = true;
        double estimate = -1.0;
        const Layers refined = test::sharedRenderer().render(scene, 0, "pcss", s, nullptr, &estimate);
        const double measured =
            compareVisibility(layer(refined, "V"), layer(truth, "V"), &layer(truth, "mask")).rmse;
        std::printf("error_target %s: estimate %.4f, measured %.4f\n", target, estimate, measured);
        EXPECT_GE(estimate, measured) << target;
        EXPECT_LE(estimate, measured + std::stod(target)) << target;
    }
}

// A GL pass that is wrongly certain everywhere (V = 1 over a soft shadow, or V = 0 over lit
// ground): the verification rays find the shadow, or the light, and the refinement traces it.
TEST(Refinement, RecoversFromAGlPassThatIsWronglyCertain) {
    Scene scene = test::sceneBox(smallSoftScene());
    const Layers truth = test::renderWith(scene, "reference", {}, 4096);
    const Image& mask = layer(truth, "mask");
    auto refineConstant = [&](float glValue, const char* verify) {
        Layers layers;
        Image v(mask.width, mask.height, 0.0f);
        for (size_t i = 0; i < v.pixels.size(); ++i) v.pixels[i] = mask.pixels[i] != 0.0f ? glValue : 0.0f;
        layers.add("V", std::move(v));
        layers.add("mask", mask);
        RenderSettings s;
        s.options = {{"refine_verify", verify}};
        TraceSceneCache cache;
        refineUncertainPixels(scene, 0, s, cache, layers);
        return layers;
    };
    for (float glValue : {1.0f, 0.0f}) {
        const Layers refined = refineConstant(glValue, "8");
        const Layers unverified = refineConstant(glValue, "0");
        const double rmse = test::compareToReference(refined, truth).rmse;
        const double rmseUnverified = test::compareToReference(unverified, truth).rmse;
        double rays = 0.0, maskCount = 0.0;
        for (size_t i = 0; i < mask.pixels.size(); ++i) {
            rays += layer(refined, "rays").pixels[i];
            maskCount += mask.pixels[i] != 0.0f;
        }
        std::printf("GL V = %.0f everywhere: RMSE %.4f refined with verification, %.4f without; %.1f rays per mask pixel\n",
                    glValue, rmse, rmseUnverified, rays / maskCount);
        EXPECT_LE(rmse, 0.01) << "GL V = " << glValue;
        EXPECT_GT(rmseUnverified, 0.05) << "GL V = " << glValue;
        // Every mask pixel took at least the verification's rays (counted in "rays").
        int unchecked = 0;
        for (size_t i = 0; i < mask.pixels.size(); ++i)
            unchecked += mask.pixels[i] != 0.0f && layer(refined, "rays").pixels[i] < 8.0f;
        EXPECT_EQ(unchecked, 0) << "GL V = " << glValue;
    }
}

// sweep shades its receiver plane only; the shadow the box casts on a low platform (another
// receiver) is V = 1 in its result. Refined, every pixel the light reaches is answered.
TEST(Refinement, AnswersEveryPixelTheLightReachesNotOnlyTheMethodsMask) {
    Scene scene = test::sceneBox(smallSoftScene());
    Mesh platform = test::makeBox({-1.2f, -1.2f, 0.0f}, {0.4f, 0.4f, 0.5f}, SS_MESH_CAST | SS_MESH_RECEIVE);
    platform.name = "platform";
    scene.addMesh(platform);
    const Layers reference = test::renderWith(scene, "reference", {}, 1024);
    const Layers plain = test::renderWith(scene, "sweep");
    const Layers refined = test::refinedWith(scene, "sweep");
    const Image& truthMask = layer(reference, "mask");
    auto rmse = [&](const Layers& l) { return compareVisibility(layer(l, "V"), layer(reference, "V"), &truthMask).rmse; };
    size_t outsidePlain = 0, outsideRefined = 0;
    for (size_t i = 0; i < truthMask.pixels.size(); ++i) {
        if (truthMask.pixels[i] == 0.0f) continue;
        outsidePlain += layer(plain, "mask").pixels[i] == 0.0f;
        outsideRefined += layer(refined, "mask").pixels[i] == 0.0f;
    }
    EXPECT_GT(outsidePlain, 300u);  // the platform's top and the box are not sweep's
    EXPECT_EQ(outsideRefined, 0u);
    EXPECT_GT(rmse(plain), 0.05);
    EXPECT_LT(rmse(refined), 0.01) << "sweep alone " << rmse(plain);
}

TEST(Refinement, EveryMethodTakesTheOptionAndItsTuningKeys) {
    Scene scene = test::sceneBox(smallSoftScene());
    for (const std::string& method : methodNames()) {
        // Whether to refine is a render option, never a method's key.
        test::expectSettingRefused(scene, method, {{"refine", "on"}}, "'refine'");
        // Final renders refine whatever method a light has: every one must take it.
        const Layers refined = test::refinedWith(scene, method, {}, 16);
        for (float v : layer(refined, "V").pixels) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << method;
    }
    test::expectSettingRefused(scene, "pcss", {{"refine_rounds", "2"}}, "'refine_rounds'");
    for (const char* key : {"refine_margin", "refine_verify"}) {
        try {
            test::refinedWith(scene, "pcss", {{key, "-1"}});
            ADD_FAILURE() << "a bad " << key << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.status(), SS_ERROR_INVALID_ARGUMENT);
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
    // The reference is exact already: refine changes nothing there.
    const Layers a = test::renderWith(scene, "reference", {}, 16);
    const Layers b = test::refinedWith(scene, "reference", {}, 16);
    EXPECT_EQ(layer(a, "V").pixels, layer(b, "V").pixels);
}

}  // namespace
}  // namespace ss
