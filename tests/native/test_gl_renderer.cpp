// Does the Renderer reuse the shared passes while a scene is unchanged, and fail clearly otherwise?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "methods/method.h"
#include "pipeline/renderer.h"
#include "test_scenes.h"

namespace ss {
namespace {

Scene twoLightScene() {
    Scene s;
    s.addMesh(test::makeGround(4.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(test::makeBox({-0.5f, -0.5f, 0.6f}, {0.5f, 0.5f, 1.0f}, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f, "A"));
    s.addLight(test::makeDiskLight({-1.0f, 0.5f, 3.0f}, 0.5f, "B"));
    s.setCamera(test::makeTopCamera(96, 72));
    return s;
}

ss_status statusOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.status();
    }
    return SS_OK;
}

TEST(GlRendererCache, SharedPassesAreDrawnOncePerSceneRevision) {
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    Layers first = renderer.render(scene, 0, "shadow_map", settings, nullptr);
    Layers again = renderer.render(scene, 0, "shadow_map", settings, nullptr);
    renderer.render(scene, 1, "shadow_map", settings, nullptr);
    Renderer::CacheStats s = renderer.cacheStats();
    EXPECT_EQ(s.frames, 1);
    EXPECT_EQ(s.meshUploads, 1);
    EXPECT_EQ(s.cameraPasses, 1);
    EXPECT_EQ(s.shadowMaps, 2);  // one per light
    EXPECT_EQ(first.find("V")->pixels, again.find("V")->pixels);

    // Any change to the scene bumps its revision: a new frame, new passes.
    scene.addLight(test::makeDiskLight({0.0f, -1.0f, 3.0f}, 0.5f, "C"));
    renderer.render(scene, 2, "shadow_map", settings, nullptr);
    s = renderer.cacheStats();
    EXPECT_EQ(s.frames, 2);
    EXPECT_EQ(s.cameraPasses, 2);
    EXPECT_EQ(s.shadowMaps, 3);
}

TEST(GlRendererCache, AutoNamesTheMethodItRan) {
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    std::string used;
    Layers layers = renderer.render(scene, 0, "auto", RenderSettings{}, &used);
    EXPECT_NE(used, "auto");
    const auto& names = methodNames();
    EXPECT_NE(std::find(names.begin(), names.end(), used), names.end()) << used;
    ASSERT_NE(layers.find("V"), nullptr);
    EXPECT_EQ(layers.find("V")->width, 96);
    EXPECT_EQ(layers.find("V")->height, 72);
}

TEST(GlRendererCache, BadRequestsAreInvalidArguments) {
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    EXPECT_EQ(statusOf([&] { renderer.render(scene, 0, "no_such_method", RenderSettings{}, nullptr); }),
              SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(statusOf([&] { renderer.render(scene, 2, "shadow_map", RenderSettings{}, nullptr); }),
              SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(statusOf([&] { renderer.render(scene, -1, "shadow_map", RenderSettings{}, nullptr); }),
              SS_ERROR_INVALID_ARGUMENT);
    Scene noCamera;
    noCamera.addLight(test::makeDiskLight({0, 0, 3}, 1.0f));
    EXPECT_NE(statusOf([&] { renderer.render(noCamera, 0, "shadow_map", RenderSettings{}, nullptr); }), SS_OK);
}

TEST(GlRendererCache, RendersAgainAfterShutdown) {
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    Layers before = renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    shutdownRenderThreads();
    // The host may shut the library down and use it again (add-on unregister, re-register):
    // a fresh thread and context are made and the result is the same.
    Layers after = renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    EXPECT_EQ(before.find("V")->pixels, after.find("V")->pixels);
    EXPECT_EQ(renderer.cacheStats().cameraPasses, 2);
}

TEST(GlRendererCache, EglAndOsmesaAgree) {
    // Both backends drive the same llvmpipe rasteriser; a difference would mean one of them
    // sets up state differently (row order, pixel centres, float targets). Exact agreement is
    // expected; one pixel in a thousand is allowed for a rasteriser tie-break on an edge.
    Scene scene = twoLightScene();
    std::vector<float> v[2];
    ss_backend backends[2] = {SS_BACKEND_EGL, SS_BACKEND_OSMESA};
    for (int i = 0; i < 2; ++i) {
        try {
            Renderer renderer(backends[i]);
            v[i] = renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr).find("V")->pixels;
        } catch (const Error& e) {
            GTEST_SKIP() << "backend " << i << " unavailable: " << e.what();
        }
    }
    ASSERT_EQ(v[0].size(), v[1].size());
    size_t differ = 0;
    for (size_t k = 0; k < v[0].size(); ++k) differ += v[0][k] != v[1][k];
    std::printf("EGL vs OSMesa: %zu of %zu pixels differ\n", differ, v[0].size());
    EXPECT_LE(differ, v[0].size() / 1000);
}

}  // namespace
}  // namespace ss
