// Checks the documented "auto" rule and that every contract method name is registered and renders.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "methods/method.h"
#include "renderer/auto_method.h"
#include "renderer/renderer.h"
#include "test_scenes.h"

namespace ss {
namespace {

Scene withLightType(LightType type, bool openCaster = false) {
    Scene s;
    // The ground casts too, as every Blender object does by default: a flat open caster.
    s.addMesh(test::makeGround(4.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    Mesh box = test::makeBox({-0.5f, -0.5f, 0.8f}, {0.5f, 0.5f, 1.2f}, SS_MESH_CAST | SS_MESH_RECEIVE);
    if (openCaster) box.triangles.pop_back();
    s.addMesh(box);
    Light l = test::makeDiskLight({0, 0, 4}, 1.0f, "Key");
    l.type = type;
    l.radius = 0.5f;
    l.angle = 0.05f;
    l.spotSize = 1.0f;
    s.addLight(l);
    s.setCamera(test::makeTopCamera(64, 48));
    return s;
}

TEST(AutoMethod, PicksTheMethodWhosePaperModelsTheLightShape) {
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Disk), 0), "dbuffer");
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Ellipse), 0), "dbuffer");
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Point), 0), "dbuffer");
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Spot), 0), "dbuffer");
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Square), 0), "occlusion_textures");
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Rectangle), 0), "occlusion_textures");
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Sun), 0), "pcss");
}

TEST(AutoMethod, OpenCastersFallBackToPcssForDiskLights) {
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Disk, true), 0), "pcss");
    EXPECT_EQ(chooseAutoMethodByShape(withLightType(LightType::Rectangle, true), 0), "occlusion_textures");
}

TEST(AutoMethod, MeasuresForEveryLightTypeAndCarriesAnEstimate) {
    Renderer renderer(SS_BACKEND_AUTO);
    for (LightType type : {LightType::Disk, LightType::Ellipse, LightType::Point, LightType::Spot, LightType::Square,
                           LightType::Rectangle, LightType::Sun}) {
        Scene scene = withLightType(type);
        std::string used;
        double estimate = -1.0;
        renderer.render(scene, 0, "auto", RenderSettings{}, &used, &estimate);
        const auto candidates = autoCandidates(scene, 0);
        EXPECT_NE(std::find(candidates.begin(), candidates.end(), used), candidates.end()) << used;
        EXPECT_TRUE(std::isfinite(estimate) && estimate >= 0.0 && estimate < 0.5)
            << int(type) << ": " << used << " " << estimate;
    }
}

TEST(AutoMethod, BadLightIndexIsAnError) {
    EXPECT_THROW(chooseAutoMethodByShape(withLightType(LightType::Disk), 3), Error);
}

TEST(MethodRegistry, EveryContractNameIsBuiltAndRendersSaneLayers) {
    const std::vector<std::string> expected = {"shadow_map", "pcss", "dbuffer", "sweep",
                                               "penumbra_map", "occlusion_textures", "reference"};
    ASSERT_EQ(methodNames(), expected);
    Scene scene = withLightType(LightType::Disk);
    Renderer renderer(SS_BACKEND_AUTO);
    for (const std::string& name : expected) {
        RenderSettings settings;
        settings.samples = name == "reference" ? 16 : 0;
        std::string used;
        Layers layers = renderer.render(scene, 0, name, settings, &used);
        EXPECT_EQ(used, name);
        const Image* v = layers.find("V");
        const Image* mask = layers.find("mask");
        ASSERT_TRUE(v && mask) << name;
        EXPECT_EQ(v->width, 64);
        EXPECT_EQ(v->height, 48);
        size_t dark = 0, masked = 0;
        for (size_t i = 0; i < v->pixels.size(); ++i) {
            ASSERT_TRUE(std::isfinite(v->pixels[i]) && v->pixels[i] >= 0.0f && v->pixels[i] <= 1.0f)
                << name << " pixel " << i << " = " << v->pixels[i];
            masked += mask->pixels[i] > 0.5f;
            dark += mask->pixels[i] > 0.5f && v->pixels[i] < 0.5f;
        }
        // The box's shadow falls on the ground in view: every method must see some of it.
        EXPECT_GT(masked, v->pixels.size() / 2) << name;
        EXPECT_GT(dark, 20u) << name;
    }
    std::string used;
    renderer.render(scene, 0, "auto", RenderSettings{}, &used);
    EXPECT_TRUE(isMethodName(used) && used != "reference") << used;
    EXPECT_THROW(createMethod("no_such_method"), Error);
}

}  // namespace
}  // namespace ss
