// Does every method honour a light's shadow linking (blockers) and light linking (receivers)?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/method_names.h"
#include "methods/method.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

constexpr uint32_t kBoth = SS_MESH_CAST | SS_MESH_RECEIVE;
constexpr int kKey = 0, kFill = 1;
constexpr int kGround = 0, kBlocker = 1, kOther = 2;

// A ground, the box `blockerFlags` makes the linked mesh, another box; Key and Fill on either
// side, each with a shadow of the first box on the ground beside it.
Scene linkScene(uint32_t blockerFlags = kBoth) {
    Scene s;
    s.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
    s.addMesh(test::makeBox({-0.7f, -0.5f, 0.6f}, {0.0f, 0.2f, 1.0f}, blockerFlags));
    s.addMesh(test::makeBox({0.4f, -0.2f, 0.4f}, {0.9f, 0.5f, 0.9f}, kBoth));
    s.addLight(test::makeDiskLight({1.2f, 0.0f, 3.0f}, 1.0f, "Key"));
    s.addLight(test::makeDiskLight({-1.4f, 0.6f, 3.0f}, 0.6f, "Fill"));
    s.setCamera(test::makeTopCamera(80, 60));
    return s;
}

LightLinks blockersWithout(int mesh) {
    LightLinks l;
    l.blockers = std::vector<int>{};
    for (int m = 0; m < 3; ++m)
        if (m != mesh) l.blockers->push_back(m);
    return l;
}

LightLinks receiversWithout(int mesh) {
    LightLinks l;
    l.receivers = std::vector<int>{};
    for (int m = 0; m < 3; ++m)
        if (m != mesh) l.receivers->push_back(m);
    return l;
}

std::vector<std::string> everyMethod() {
    std::vector<std::string> out = methodNames();
    out.push_back("auto");
    return out;
}

int differingPixels(const Image& a, const Image& b, float by) {
    int n = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) n += std::fabs(a.pixels[i] - b.pixels[i]) > by;
    return n;
}

// RMSE of V over the pixels both masks hold.
double rmseInMasks(const Layers& a, const Layers& b) {
    const Image &va = *a.find("V"), &vb = *b.find("V"), &ma = *a.find("mask"), &mb = *b.find("mask");
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < va.pixels.size(); ++i) {
        if (ma.pixels[i] < 0.5f || mb.pixels[i] < 0.5f) continue;
        const double d = double(va.pixels[i]) - double(vb.pixels[i]);
        sum += d * d;
        ++n;
    }
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

// What each method's V may be off the reference's on this scene (measured 0.048, 0.005, 0.023,
// 0.006, 0.045, 0.030, 0, 0.005): the linked light's pass is as good as an unlinked one.
const std::map<std::string, double> kBoundVsReference = {
    {"shadow_map", 0.07}, {"pcss", 0.02}, {"dbuffer", 0.04}, {"sweep", 0.02},
    {"penumbra_map", 0.07}, {"occlusion_textures", 0.05}, {"reference", 0.0}, {"auto", 0.02}};

TEST(LightLinksRender, AnExcludedBlockerShadowsNothingOfThatLightInEveryMethod) {
    Scene linked = linkScene();
    linked.setLightLinks(kKey, blockersWithout(kBlocker));
    const Scene unlinked = linkScene();
    const Scene noCaster = linkScene(SS_MESH_RECEIVE);  // what Key should see: the box casts nothing
    Renderer renderer(SS_BACKEND_AUTO);
    const Layers truth = renderer.render(linked, kKey, "reference", RenderSettings{}, nullptr);
    for (const std::string& method : everyMethod()) {
        SCOPED_TRACE(method);
        const Layers key = renderer.render(linked, kKey, method, RenderSettings{}, nullptr);
        const Layers keyNoCaster = renderer.render(noCaster, kKey, method, RenderSettings{}, nullptr);
        const Layers keyUnlinked = renderer.render(unlinked, kKey, method, RenderSettings{}, nullptr);
        EXPECT_EQ(key.find("V")->pixels, keyNoCaster.find("V")->pixels);
        EXPECT_EQ(key.find("mask")->pixels, keyNoCaster.find("mask")->pixels);
        // The box's shadow is there to take away: unlinked, it darkens many pixels.
        EXPECT_GT(differingPixels(*keyUnlinked.find("V"), *keyNoCaster.find("V"), 0.2f), 60);
        EXPECT_LE(rmseInMasks(key, truth), kBoundVsReference.at(method));

        // Fill is not linked: the box still shadows it, exactly as without links.
        const Layers fill = renderer.render(linked, kFill, method, RenderSettings{}, nullptr);
        const Layers fillUnlinked = renderer.render(unlinked, kFill, method, RenderSettings{}, nullptr);
        const Layers fillNoCaster = renderer.render(noCaster, kFill, method, RenderSettings{}, nullptr);
        EXPECT_EQ(fill.find("V")->pixels, fillUnlinked.find("V")->pixels);
        EXPECT_GT(differingPixels(*fill.find("V"), *fillNoCaster.find("V"), 0.2f), 60);
    }
}

TEST(LightLinksRender, NoBlockerAtAllLeavesEveryReceiverLit) {
    Scene linked = linkScene();
    LightLinks none;
    none.blockers = std::vector<int>{};  // a rim light nothing blocks
    linked.setLightLinks(kKey, none);
    Renderer renderer(SS_BACKEND_AUTO);
    for (const std::string& method : everyMethod()) {
        SCOPED_TRACE(method);
        const Layers key = renderer.render(linked, kKey, method, RenderSettings{}, nullptr);
        const Image& v = *key.find("V");
        const Image& mask = *key.find("mask");
        int inMask = 0, shadowed = 0;
        for (size_t i = 0; i < v.pixels.size(); ++i) {
            if (mask.pixels[i] < 0.5f) continue;
            ++inMask;
            shadowed += v.pixels[i] < 0.99f;
        }
        EXPECT_GT(inMask, 1000);
        EXPECT_LE(shadowed, inMask / 200) << "of " << inMask;  // a method's own acne, at most
    }
}

TEST(LightLinksRender, AnUnlitReceiverLeavesTheLightsMaskInEveryMethod) {
    Scene linked = linkScene();
    linked.setLightLinks(kKey, receiversWithout(kBlocker));
    const Scene unlinked = linkScene();
    const Scene notReceiving = linkScene(SS_MESH_CAST);  // what Key should see: the box takes no light
    Renderer renderer(SS_BACKEND_AUTO);
    for (const std::string& method : everyMethod()) {
        SCOPED_TRACE(method);
        const Layers key = renderer.render(linked, kKey, method, RenderSettings{}, nullptr);
        const Layers keyNotReceiving = renderer.render(notReceiving, kKey, method, RenderSettings{}, nullptr);
        const Layers keyUnlinked = renderer.render(unlinked, kKey, method, RenderSettings{}, nullptr);
        EXPECT_EQ(key.find("mask")->pixels, keyNotReceiving.find("mask")->pixels);
        // The box's top leaves the mask (sweep shades its receiver plane only: never the box).
        if (method != "sweep") EXPECT_GT(differingPixels(*key.find("mask"), *keyUnlinked.find("mask"), 0.5f), 30);
        // Where the box is, V = 1 (no shadow owed); elsewhere as it was.
        const Image &v = *key.find("V"), &mask = *key.find("mask"), &maskUnlinked = *keyUnlinked.find("mask");
        for (size_t i = 0; i < v.pixels.size(); ++i) {
            if (mask.pixels[i] < 0.5f && maskUnlinked.pixels[i] > 0.5f) {
                ASSERT_EQ(v.pixels[i], 1.0f) << "pixel " << i;
            } else if (mask.pixels[i] > 0.5f) {
                ASSERT_EQ(v.pixels[i], keyUnlinked.find("V")->pixels[i]) << "pixel " << i;
            }
        }
        // Fill still lights the box.
        const Layers fill = renderer.render(linked, kFill, method, RenderSettings{}, nullptr);
        const Layers fillUnlinked = renderer.render(unlinked, kFill, method, RenderSettings{}, nullptr);
        EXPECT_EQ(fill.find("mask")->pixels, fillUnlinked.find("mask")->pixels);
        EXPECT_EQ(fill.find("V")->pixels, fillUnlinked.find("V")->pixels);
    }
}

TEST(LightLinksRender, ALinkEditRedrawsThatLightOnlyAndRendersAsAFreshScene) {
    Scene scene = linkScene();
    Renderer warm(SS_BACKEND_AUTO);
    std::vector<std::string> methods;
    for (const std::string& name : methodNames())
        if (createMethod(name)->needsGl()) methods.push_back(name);
    for (const std::string& method : methods) {
        warm.render(scene, kKey, method, RenderSettings{}, nullptr);
        warm.render(scene, kFill, method, RenderSettings{}, nullptr);
    }
    warm.render(scene, kKey, "reference", RenderSettings{}, nullptr);
    const int maps = warm.cacheStats().shadowMaps;
    LightLinks links = blockersWithout(kBlocker);
    links.receivers = std::vector<int>{kGround, kOther};
    scene.setLightLinks(kKey, links);

    Scene fresh = linkScene();
    fresh.setLightLinks(kKey, links);
    Renderer cold(SS_BACKEND_AUTO);
    for (const std::string& method : methods) {
        SCOPED_TRACE(method);
        for (int light : {kKey, kFill}) {
            const Layers a = warm.render(scene, light, method, RenderSettings{}, nullptr);
            const Layers b = cold.render(fresh, light, method, RenderSettings{}, nullptr);
            EXPECT_EQ(a.find("V")->pixels, b.find("V")->pixels) << "light " << light;
            EXPECT_EQ(a.find("mask")->pixels, b.find("mask")->pixels) << "light " << light;
        }
    }
    const Layers a = warm.render(scene, kKey, "reference", RenderSettings{}, nullptr);
    const Layers b = cold.render(fresh, kKey, "reference", RenderSettings{}, nullptr);
    EXPECT_EQ(a.find("V")->pixels, b.find("V")->pixels);
    // Only Key's map was drawn again (once per map size the methods use), Fill's kept.
    const int redrawn = warm.cacheStats().shadowMaps - maps;
    EXPECT_GE(redrawn, 1);
    EXPECT_EQ(redrawn, cold.cacheStats().shadowMaps / 2);

    // The same links again change nothing: no map is drawn.
    scene.setLightLinks(kKey, links);
    const int before = warm.cacheStats().shadowMaps;
    for (const std::string& method : methods) warm.render(scene, kKey, method, RenderSettings{}, nullptr);
    EXPECT_EQ(warm.cacheStats().shadowMaps, before);
}

}  // namespace
}  // namespace ss
