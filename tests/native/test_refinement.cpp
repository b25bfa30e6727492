// Checks "refine=on" for the GL methods: untouched where the pass is certain, closer to the truth elsewhere.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "io/metrics.h"
#include "renderer/refinement.h"
#include "test_pcss_support.h"

namespace ss {
namespace {

const Image& layer(const Layers& layers, const char* name) {
    const Image* img = layers.find(name);
    if (!img) throw std::runtime_error(std::string("missing layer ") + name);
    return *img;
}

test::SceneParams smallSoftScene() {
    test::SceneParams p = test::softSceneParams();
    p.width = 96;
    p.height = 72;
    return p;
}

TEST(Refinement, IdenticalToTheGlResultWhereThePassIsCertain) {
    Scene scene = test::sceneBox(smallSoftScene());
    for (const char* method : {"pcss", "shadow_map", "penumbra_map"}) {
        const Layers gl = test::renderWith(scene, method);
        const Layers refined = test::renderWith(scene, method, {{"refine", "on"}});
        const Image &vGl = layer(gl, "V"), &vRef = layer(refined, "V"), &traced = layer(refined, "refined");
        const Image expected = uncertainPixels(vGl, layer(gl, "mask"), 3);
        EXPECT_EQ(traced.pixels, expected.pixels) << method;
        int certain = 0, changed = 0;
        for (size_t i = 0; i < vGl.pixels.size(); ++i) {
            if (traced.pixels[i] == 0.0f) {
                ++certain;
                EXPECT_EQ(vRef.pixels[i], vGl.pixels[i]) << method << " pixel " << i;
                EXPECT_EQ(layer(refined, "rays").pixels[i], 0.0f);
            } else if (vRef.pixels[i] != vGl.pixels[i]) {
                ++changed;
            }
        }
        EXPECT_GT(certain, int(vGl.pixels.size() / 2)) << method;
        EXPECT_GT(changed, 0) << method;
        // The method's own layers stay, mask included, in their order; refinement adds two.
        EXPECT_EQ(layer(refined, "mask").pixels, layer(gl, "mask").pixels) << method;
        ASSERT_EQ(refined.items.size(), gl.items.size() + 2) << method;
        size_t k = 0;
        for (const auto& [name, image] : gl.items) {
            if (name == "umbra" || name == "penumbra") continue;
            while (refined.items[k].first != name) ++k;
            if (name != "V") EXPECT_EQ(refined.items[k].second.pixels, image.pixels) << method << " " << name;
        }
    }
}

TEST(Refinement, CloserToA4096SampleReferenceThanTheGlMethodAlone) {
    Scene scene = test::sceneBox(smallSoftScene());
    const Layers truth = test::renderWith(scene, "reference", {}, 4096);
    for (const char* method : {"pcss", "shadow_map"}) {
        const Layers gl = test::renderWith(scene, method);
        const Layers refined = test::renderWith(scene, method, {{"refine", "on"}});
        const Metrics a = test::compareToReference(gl, truth), b = test::compareToReference(refined, truth);
        double traced = 0.0;
        for (float v : layer(refined, "refined").pixels) traced += v;
        std::printf("%s: RMSE %.4f alone, %.4f refined (%.0f%% of pixels traced)\n", method, a.rmse,
                    b.rmse, 100.0 * traced / double(layer(gl, "V").pixels.size()));
        EXPECT_LT(b.rmse, a.rmse) << method;
        EXPECT_LT(b.rmse, 0.5 * a.rmse) << method;
    }
}

TEST(Refinement, EveryMethodAcceptsTheKeyAndRefusesABadValue) {
    Scene scene = test::sceneBox(smallSoftScene());
    for (const std::string& method : methodNames()) {
        test::expectSettingRefused(scene, method, {{"refine", "maybe"}}, "refine");
        // Final renders add refine=on to whatever method a light has: every one must take it.
        const Layers refined = test::renderWith(scene, method, {{"refine", "on"}}, 16);
        for (float v : layer(refined, "V").pixels) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << method;
    }
    test::expectSettingRefused(scene, "pcss", {{"refine", "on"}, {"refine_margin", "-1"}}, "refine_margin");
    // The reference is exact already: refine changes nothing there.
    const Layers a = test::renderWith(scene, "reference", {}, 16);
    const Layers b = test::renderWith(scene, "reference", {{"refine", "on"}}, 16);
    EXPECT_EQ(layer(a, "V").pixels, layer(b, "V").pixels);
}

}  // namespace
}  // namespace ss
