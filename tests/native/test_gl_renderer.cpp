// Does the Renderer reuse the shared passes while a scene is unchanged, and fail clearly otherwise?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <atomic>
#include <chrono>
#include <string>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/visibility_classes.h"
#include "gl/render_thread.h"
#include "methods/method.h"
#include "renderer/renderer.h"
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

using test::statusOf;

TEST(GlRendererCache, SharedPassesAreDrawnOnceUntilTheirInputsChange) {
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    Layers first = renderer.render(scene, 0, "shadow_map", settings, nullptr);
    Layers again = renderer.render(scene, 0, "shadow_map", settings, nullptr);
    renderer.render(scene, 1, "shadow_map", settings, nullptr);
    Renderer::CacheStats s = renderer.cacheStats();
    EXPECT_EQ(s.sceneCaches, 1);
    EXPECT_EQ(s.meshUploads, 2);  // each mesh once
    EXPECT_EQ(s.cameraPasses, 1);
    EXPECT_EQ(s.shadowMaps, 2);  // one per light
    EXPECT_EQ(first.find("V")->pixels, again.find("V")->pixels);

    // An edit keeps the frame and redraws only what it changed: a new light, a new map.
    scene.addLight(test::makeDiskLight({0.0f, -1.0f, 3.0f}, 0.5f, "C"));
    renderer.render(scene, 2, "shadow_map", settings, nullptr);
    s = renderer.cacheStats();
    EXPECT_EQ(s.sceneCaches, 1);
    EXPECT_EQ(s.cameraPasses, 1);
    EXPECT_EQ(s.shadowMaps, 3);
    // A copy is another scene: a frame of its own.
    Scene copy = scene;
    renderer.render(copy, 0, "shadow_map", settings, nullptr);
    EXPECT_EQ(renderer.cacheStats().sceneCaches, 2);
}

// Every GL method resolves over the camera pass on the GPU and reads back only its layers: the
// camera pass itself (48 MB at 1024²) stays there. The sweep's raster=cpu cross-check is the one
// reader, which shows the count counts.
TEST(GlRendererCache, NoGlMethodReadsTheCameraPassBack) {
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    for (const std::string& name : methodNames()) {
        if (name == "reference") continue;
        renderer.render(scene, 0, name, settings, nullptr);
        EXPECT_EQ(renderer.cacheStats().cameraReadbacks, 0) << name;
    }
    settings.options = {{"raster", "cpu"}};
    renderer.render(scene, 0, "sweep", settings, nullptr);
    EXPECT_EQ(renderer.cacheStats().cameraReadbacks, 1);
}

// What a method makes from the light and the geometry alone (sweep's shadow mesh,
// occlusion_textures' slices, dbuffer's D-buffer) is kept through a camera edit, and made again
// (or patched) after a move; every time the layers are those of a renderer that never saw the
// scene before.
TEST(GlRendererCache, LightWorkIsKeptThroughACameraEditAndMadeAgainAfterAMove) {
    RenderSettings settings;
    auto fresh = [&](const Scene& scene, const std::string& name) {
        Renderer other(SS_BACKEND_AUTO);
        return other.render(scene, 0, name, settings, nullptr);
    };
    // Every layer, the methods' debug layers too (dbuffer's distances read its D-buffer).
    auto expectSame = [](const Layers& a, const Layers& b) {
        ASSERT_EQ(a.items.size(), b.items.size());
        for (size_t i = 0; i < a.items.size(); ++i) {
            EXPECT_EQ(a.items[i].first, b.items[i].first);
            EXPECT_EQ(a.items[i].second.pixels, b.items[i].second.pixels) << a.items[i].first;
        }
    };
    for (const std::string name : {"occlusion_textures", "sweep", "dbuffer"}) {
        SCOPED_TRACE(name);
        Scene scene = twoLightScene();
        Renderer renderer(SS_BACKEND_AUTO);
        renderer.render(scene, 0, name, settings, nullptr);
        EXPECT_EQ(renderer.cacheStats().lightWorkMade, 1);

        scene.setCamera(makeLookAtCamera({2.0f, -3.0f, 6.0f}, {0.0f, 0.0f, 0.3f}, {0.0f, 0.0f, 1.0f},
                                         glm::radians(40.0f), 96, 72, 0.1f, 50.0f));
        Layers orbited = renderer.render(scene, 0, name, settings, nullptr);
        EXPECT_EQ(renderer.cacheStats().lightWorkMade, 1);
        EXPECT_GE(renderer.cacheStats().lightWorkKept, 1);
        expectSame(orbited, fresh(scene, name));

        // occlusion_textures redraws its slices where the box was and is (the move keeps their
        // fit); the sweep makes its shadow again from the meshes' kept projections, dbuffer its
        // D-buffer from the volumes (the moved box's made again, the others kept).
        const bool patches = name == "occlusion_textures";
        scene.setMeshTransform(1, glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, 0.0f, 0.0f)));
        Layers moved = renderer.render(scene, 0, name, settings, nullptr);
        EXPECT_EQ(renderer.cacheStats().lightWorkMade, patches ? 1 : 2);
        EXPECT_EQ(renderer.cacheStats().lightWorkPatched, patches ? 1 : 0);
        expectSame(moved, fresh(scene, name));
        EXPECT_NE(moved.find("V")->pixels, orbited.find("V")->pixels);  // the shadow moved with the box

        // A move that changes the fit (the box rises above the scene's old bounds) draws all.
        scene.setMeshTransform(1, glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, 0.0f, 1.5f)));
        Layers risen = renderer.render(scene, 0, name, settings, nullptr);
        EXPECT_EQ(renderer.cacheStats().lightWorkMade, patches ? 2 : 3);
        expectSame(risen, fresh(scene, name));
    }
}

// Each light keeps its own slices: render_passes renders every light in turn on every frame.
TEST(GlRendererCache, OcclusionTexturesKeepEachLightsSlices) {
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    Layers first = renderer.render(scene, 0, "occlusion_textures", settings, nullptr);
    renderer.render(scene, 1, "occlusion_textures", settings, nullptr);
    Layers again = renderer.render(scene, 0, "occlusion_textures", settings, nullptr);
    renderer.render(scene, 1, "occlusion_textures", settings, nullptr);
    EXPECT_EQ(renderer.cacheStats().lightWorkMade, 2);
    EXPECT_EQ(renderer.cacheStats().lightWorkKept, 2);
    EXPECT_EQ(first.find("V")->pixels, again.find("V")->pixels);

    // Removing light 0 moves B to index 0: its slices are drawn for it, not taken from A's.
    scene.removeLight(0);
    Layers moved = renderer.render(scene, 0, "occlusion_textures", settings, nullptr);
    EXPECT_EQ(renderer.cacheStats().lightWorkMade, 3);
    Renderer other(SS_BACKEND_AUTO);
    EXPECT_EQ(moved.find("V")->pixels, other.render(scene, 0, "occlusion_textures", settings, nullptr).find("V")->pixels);
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

TEST(GlRendererCache, ShutdownWhileARenderHoldsTheCacheFailsCleanly) {
    // ss_shutdown from another thread may land after render() took the cache entry and before
    // GL work starts: here from auto's progress report before its first candidate, once the
    // sparse check took the frame's ray-tracing scene. What the render holds must stay alive:
    // the render fails with SS_ERROR_GL (the thread is gone), and the next one starts afresh.
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    Layers before = renderer.render(scene, 0, "auto", RenderSettings{}, nullptr);
    int shutdowns = 0;
    RenderSettings stopping;
    stopping.progress = [&](float, const char* stage) {
        if (std::string(stage).rfind("auto: trying ", 0) == 0 && shutdowns++ == 0) shutdownRenderThreads();
        return true;
    };
    EXPECT_EQ(statusOf([&] { renderer.render(scene, 0, "auto", stopping, nullptr); }), SS_ERROR_GL);
    EXPECT_EQ(shutdowns, 1);
    Layers after = renderer.render(scene, 0, "auto", RenderSettings{}, nullptr);
    EXPECT_EQ(before.find("V")->pixels, after.find("V")->pixels);
}

TEST(GlRendererCache, ShutdownStressDuringRendersNeverCrashes) {
    // ss_shutdown on one thread while another renders: every render either succeeds with the
    // right picture or fails with SS_ERROR_GL.
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    const std::vector<float> expected = renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr).find("V")->pixels;
    std::atomic<bool> done{false};
    std::thread stopper([&] {
        while (!done) {
            shutdownRenderThreads();
            std::this_thread::sleep_for(std::chrono::milliseconds(3));
        }
    });
    int ok = 0, refused = 0;
    for (int i = 0; i < 40; ++i) {
        try {
            Layers l = renderer.render(scene, i % 2, "shadow_map", RenderSettings{}, nullptr);
            if (i % 2 == 0) {
                EXPECT_EQ(l.find("V")->pixels, expected);
            }
            ++ok;
        } catch (const Error& e) {
            EXPECT_EQ(e.status(), SS_ERROR_GL) << e.what();
            ++refused;
        }
    }
    done = true;
    stopper.join();
    EXPECT_EQ(ok + refused, 40);
}

TEST(GlRendererSettings, AnUnknownKeyIsRefusedNamingItAndTheKnownKeys) {
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    settings.options = {{"blocker_sample", "64"}};  // a typo of blocker_samples
    try {
        renderer.render(scene, 0, "pcss", settings, nullptr);
        ADD_FAILURE() << "the unknown key was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_ARGUMENT);
        EXPECT_EQ(
            std::string(e.what()),
            "method 'pcss' has no setting 'blocker_sample' (its settings: blocker_samples, pcf_samples, "
            "shadow_map_size, max_search, estimate_rmse, refine_margin, refine_samples, refine_verify, "
            "error_target, guard_band, memory_limit_mb)");
    }
    // Every method refuses an unknown key, CPU and GL alike, and before any work.
    for (const std::string& method : methodNames()) {
        RenderSettings typo;
        typo.options = {{"no_such_setting", "1"}};
        EXPECT_EQ(statusOf([&] { renderer.render(scene, 0, method, typo, nullptr); }), SS_ERROR_INVALID_ARGUMENT)
            << method;
    }
}

TEST(GlRendererSettings, EveryMethodsKeysAreAcceptedWithTheirDefaults) {
    // Each entry of each table is accepted with its own default written out.
    for (const std::string& name : methodNames()) {
        auto m = createMethod(name);
        EXPECT_EQ(m->name(), name);
        const SettingTable table = renderSettingTable(name);
        RenderSettings s;
        for (const SettingSpec& spec : table)
            if (spec.type != SettingType::Text && !spec.renderDefault) s.options[spec.key] = spec.defaultText();
        EXPECT_NO_THROW(s.requireKnownKeys(name, table)) << name;
        for (const SettingSpec& spec : m->settingTable()) EXPECT_NE(findSetting(table, spec.key), nullptr) << name;
    }
}

TEST(GlRendererLayers, UmbraAndPenumbraAreTheClassesOfVForEveryMethod) {
    // One meaning for every method: umbra = mask and V < 0.05, penumbra = mask and
    // 0.05 <= V <= 0.95 (core/visibility_classes.h), placed right after the mask.
    Scene scene = twoLightScene();
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    settings.samples = 16;
    for (const std::string& method : methodNames()) {
        Layers layers;
        try {
            layers = renderer.render(scene, 0, method, settings, nullptr);
        } catch (const Error& e) {
            ADD_FAILURE() << method << ": " << e.what();
            continue;
        }
        ASSERT_GE(layers.items.size(), 4u) << method;
        EXPECT_EQ(layers.items[0].first, "V") << method;
        EXPECT_EQ(layers.items[1].first, "mask") << method;
        EXPECT_EQ(layers.items[2].first, "umbra") << method;
        EXPECT_EQ(layers.items[3].first, "penumbra") << method;
        const Image& v = *layers.find("V");
        const Image& mask = *layers.find("mask");
        const Image& umbra = *layers.find("umbra");
        const Image& penumbra = *layers.find("penumbra");
        size_t wrong = 0, umbraPixels = 0;
        for (size_t i = 0; i < v.pixels.size(); ++i) {
            bool in = mask.pixels[i] > 0.5f;
            wrong += umbra.pixels[i] != ((in && v.pixels[i] < 0.05f) ? 1.0f : 0.0f);
            wrong += penumbra.pixels[i] != ((in && v.pixels[i] >= 0.05f && v.pixels[i] <= 0.95f) ? 1.0f : 0.0f);
            umbraPixels += umbra.pixels[i] == 1.0f;
        }
        EXPECT_EQ(wrong, 0u) << method;
        EXPECT_GT(umbraPixels, 0u) << method << ": the box casts an umbra";
    }
    RenderSettings plain;
    plain.extraLayers = false;
    Layers only = renderer.render(scene, 0, "pcss", plain, nullptr);
    EXPECT_EQ(only.items.size(), 2u);
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
