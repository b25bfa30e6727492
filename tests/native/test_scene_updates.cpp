// Does an edited scene keep the caches of what the edit left alone, and render as a fresh one?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/method_names.h"
#include "scene_cache/scene_cache.h"
#include "methods/method.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

constexpr uint32_t kBoth = SS_MESH_CAST | SS_MESH_RECEIVE;

Mesh boxA() { return test::makeBox({-0.9f, -0.5f, 0.6f}, {-0.2f, 0.2f, 1.0f}, kBoth); }
Mesh boxB() { return test::makeBox({0.3f, -0.2f, 0.4f}, {0.8f, 0.5f, 0.9f}, kBoth); }
Mesh boxBEdited() { return test::makeBox({0.2f, -0.4f, 0.5f}, {0.9f, 0.3f, 1.1f}, kBoth); }

// Mesh `m` through the C API, placed by `objectToWorld` (nullptr: the identity).
ss_status addMeshThroughCApi(ss_scene* scene, const Mesh& m, const float* objectToWorld, const char* name = nullptr) {
    std::vector<float> xyz;
    for (const glm::vec3& p : m.objectPositions) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    return ss_scene_add_mesh(scene, name ? name : m.name.c_str(), xyz.data(), uint32_t(m.objectPositions.size()),
                             &m.triangles[0][0], uint32_t(m.triangles.size()), objectToWorld, kBoth, nullptr);
}

// Light "A" of threeMeshTwoLights() as the C API takes it.
ss_light_desc lightADesc() {
    ss_light_desc light{};
    light.name = "A";
    light.type = SS_LIGHT_DISK;
    const glm::mat4 at = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.3f, 4.0f));
    for (int i = 0; i < 16; ++i) light.light_to_world[i] = (&at[0][0])[i];
    light.size = light.size_y = 1.0f;
    light.cast_shadows = 1;
    return light;
}

// test::makeTopCamera(64, 48) as the C API takes it.
ss_camera_desc topCameraDesc() {
    const Camera cam = test::makeTopCamera(64, 48);
    ss_camera_desc camera{};
    for (int i = 0; i < 16; ++i) {
        camera.world_to_camera[i] = (&cam.worldToCamera[0][0])[i];
        camera.projection[i] = (&cam.projection[0][0])[i];
    }
    camera.width = cam.width;
    camera.height = cam.height;
    camera.pixel_aspect = 1.0f;
    return camera;
}

Scene threeMeshTwoLights() {
    Scene s;
    s.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
    s.addMesh(boxA());
    s.addMesh(boxB());
    s.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f, "A"));
    s.addLight(test::makeDiskLight({-1.0f, 0.5f, 3.0f}, 0.5f, "B"));
    s.setCamera(test::makeTopCamera(64, 48));
    return s;
}

std::vector<std::string> glMethods() {
    std::vector<std::string> out;
    for (const std::string& name : methodNames())
        if (createMethod(name)->needsGl()) out.push_back(name);
    return out;
}

// Every GL method's V of every light of `edited` (rendered by a renderer that saw the scene
// before the edit) equals a fresh renderer's on a freshly built `fresh`.
void expectSameAsFresh(Renderer& warm, const Scene& edited, const Scene& fresh) {
    ASSERT_EQ(edited.lights().size(), fresh.lights().size());
    Renderer cold(SS_BACKEND_AUTO);
    for (const std::string& method : glMethods())
        for (int light = 0; light < int(edited.lights().size()); ++light) {
            Layers a = warm.render(edited, light, method, RenderSettings{}, nullptr);
            Layers b = cold.render(fresh, light, method, RenderSettings{}, nullptr);
            EXPECT_EQ(a.find("V")->pixels, b.find("V")->pixels) << method << ", light " << light;
            EXPECT_EQ(a.find("mask")->pixels, b.find("mask")->pixels) << method << ", light " << light;
        }
}

TEST(SceneUpdates, ALightEditRedrawsOnlyThatLightsShadowMap) {
    Scene scene = threeMeshTwoLights();
    Renderer renderer(SS_BACKEND_AUTO);
    renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    renderer.render(scene, 1, "shadow_map", RenderSettings{}, nullptr);
    Renderer::CacheStats before = renderer.cacheStats();
    EXPECT_EQ(before.meshUploads, 3);
    EXPECT_EQ(before.shadowMaps, 2);

    Light moved = test::makeDiskLight({-0.6f, 0.9f, 3.2f}, 0.7f, "B");
    scene.updateLight(1, moved);
    renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    renderer.render(scene, 1, "shadow_map", RenderSettings{}, nullptr);
    Renderer::CacheStats after = renderer.cacheStats();
    EXPECT_EQ(after.sceneCaches, 1);
    EXPECT_EQ(after.meshUploads, 3);       // no mesh sent again
    EXPECT_EQ(after.cameraPasses, 1);      // the camera sees no change
    EXPECT_EQ(after.shadowMaps, 3);        // light A's map reused, B's redrawn

    Scene fresh;
    fresh.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
    fresh.addMesh(boxA());
    fresh.addMesh(boxB());
    fresh.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f, "A"));
    fresh.addLight(moved);
    fresh.setCamera(test::makeTopCamera(64, 48));
    expectSameAsFresh(renderer, scene, fresh);
}

TEST(SceneUpdates, AMeshEditUploadsOnlyThatMesh) {
    Scene scene = threeMeshTwoLights();
    Renderer renderer(SS_BACKEND_AUTO);
    renderer.render(scene, 0, "pcss", RenderSettings{}, nullptr);
    ASSERT_EQ(renderer.cacheStats().meshUploads, 3);

    scene.updateMesh(2, boxBEdited());
    Layers after = renderer.render(scene, 0, "pcss", RenderSettings{}, nullptr);
    Renderer::CacheStats s = renderer.cacheStats();
    EXPECT_EQ(s.sceneCaches, 1);
    EXPECT_EQ(s.meshUploads, 4);   // the edited mesh alone
    EXPECT_EQ(s.cameraPasses, 2);  // the camera sees every mesh
    EXPECT_EQ(s.shadowMaps, 2);    // and so does the light

    Scene fresh;
    fresh.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
    fresh.addMesh(boxA());
    fresh.addMesh(boxBEdited());
    fresh.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f, "A"));
    fresh.addLight(test::makeDiskLight({-1.0f, 0.5f, 3.0f}, 0.5f, "B"));
    fresh.setCamera(test::makeTopCamera(64, 48));
    expectSameAsFresh(renderer, scene, fresh);
}

TEST(SceneUpdates, AMovedMeshCostsAMatrixAndRendersAsTheMovedGeometry) {
    Scene scene = threeMeshTwoLights();
    Renderer renderer(SS_BACKEND_AUTO);
    Layers before = renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    const size_t edgesBefore = scene.meshes()[1].adjacency.edges.size();

    glm::mat4 move = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, 0.6f, 0.0f)), 0.3f,
                                 glm::vec3(0, 0, 1));
    scene.setMeshTransform(1, move);
    Layers moved = renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    EXPECT_EQ(renderer.cacheStats().meshUploads, 3);  // the moved mesh is drawn with its matrix
    EXPECT_EQ(renderer.cacheStats().cameraPasses, 2);
    EXPECT_EQ(renderer.cacheStats().shadowMaps, 2);
    // Redrawn only where the box was and is (the scene bounds, so the map's fit, are the ground's).
    EXPECT_EQ(renderer.cacheStats().cameraPassesPatched, 1);
    EXPECT_EQ(renderer.cacheStats().shadowMapsPatched, 1);
    EXPECT_EQ(scene.meshes()[1].adjacency.edges.size(), edgesBefore);
    EXPECT_NE(before.find("V")->pixels, moved.find("V")->pixels);  // the shadow moved

    Mesh a = boxA();
    for (glm::vec3& p : a.objectPositions) p = glm::vec3(move * glm::vec4(p, 1.0f));
    Scene fresh;
    fresh.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
    fresh.addMesh(a);
    fresh.addMesh(boxB());
    fresh.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f, "A"));
    fresh.addLight(test::makeDiskLight({-1.0f, 0.5f, 3.0f}, 0.5f, "B"));
    fresh.setCamera(test::makeTopCamera(64, 48));
    expectSameAsFresh(renderer, scene, fresh);

    // A second move starts from the coordinates as given, not from the last placement.
    scene.setMeshTransform(1, glm::mat4(1.0f));
    EXPECT_EQ(scene.meshes()[1].positions, boxA().objectPositions);

    // A move that raises the scene's top changes every map's fit: the maps are redrawn whole,
    // the camera pass is still patched, and the result is still a fresh scene's.
    const Renderer::CacheStats settled = renderer.cacheStats();
    const glm::mat4 raise = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 0.5f));
    scene.setMeshTransform(1, raise);
    renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    EXPECT_EQ(renderer.cacheStats().shadowMapsPatched, settled.shadowMapsPatched);
    EXPECT_EQ(renderer.cacheStats().shadowMaps, settled.shadowMaps + 1);
    EXPECT_EQ(renderer.cacheStats().cameraPassesPatched, settled.cameraPassesPatched + 1);
    Mesh raised = boxA();
    for (glm::vec3& p : raised.objectPositions) p = glm::vec3(raise * glm::vec4(p, 1.0f));
    Scene fresh2;
    fresh2.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
    fresh2.addMesh(raised);
    fresh2.addMesh(boxB());
    fresh2.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f, "A"));
    fresh2.addLight(test::makeDiskLight({-1.0f, 0.5f, 3.0f}, 0.5f, "B"));
    fresh2.setCamera(test::makeTopCamera(64, 48));
    expectSameAsFresh(renderer, scene, fresh2);
}

// Where the shadow of a point on the ground plane z = 0 falls in the image: V at that pixel.
float vAtShadowOf(const Layers& layers, const Scene& scene, const glm::vec3& light, const glm::vec3& point) {
    glm::vec3 onGround = light + (point - light) * (light.z / (light.z - point.z));
    glm::vec4 clip = scene.camera().worldToClip() * glm::vec4(onGround, 1.0f);
    const Image& v = *layers.find("V");
    int x = int((clip.x / clip.w * 0.5f + 0.5f) * float(v.width));
    int y = int((0.5f - clip.y / clip.w * 0.5f) * float(v.height));
    return v.pixels[size_t(y) * size_t(v.width) + size_t(x)];
}

// Every GL method on the second frame of an animation: the moved box is not uploaded again (nor
// is anything else), and its shadow leaves the old place for the new one.
TEST(SceneUpdates, EveryGlMethodDrawsAMovedMeshWithItsMatrixAndTheShadowFollows) {
    const glm::vec3 light(2.5f, 0.0f, 4.0f), centre(-0.6f, 0.0f, 0.8f), shift(1.2f, 0.0f, 0.0f);
    for (const std::string& method : glMethods()) {
        Scene scene;
        scene.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
        scene.addMesh(test::makeBox(centre - glm::vec3(0.3f, 0.3f, 0.2f), centre + glm::vec3(0.3f, 0.3f, 0.2f), kBoth));
        scene.addLight(test::makeDiskLight(light, 0.2f, "Key"));
        scene.setCamera(test::makeTopCamera(96, 72));
        Renderer renderer(SS_BACKEND_AUTO);
        Layers before = renderer.render(scene, 0, method, RenderSettings{}, nullptr);
        ASSERT_EQ(renderer.cacheStats().meshUploads, 2) << method;

        scene.setMeshTransform(1, glm::translate(glm::mat4(1.0f), shift));
        Layers after = renderer.render(scene, 0, method, RenderSettings{}, nullptr);
        Renderer::CacheStats s = renderer.cacheStats();
        EXPECT_EQ(s.meshUploads, 2) << method << ": a move uploads nothing";
        EXPECT_EQ(s.cameraPasses, 2) << method;
        EXPECT_EQ(s.cameraPassesPatched, 1) << method << ": redrawn only where the box was and is";
        EXPECT_LT(vAtShadowOf(before, scene, light, centre), 0.1f) << method;
        EXPECT_GT(vAtShadowOf(before, scene, light, centre + shift), 0.9f) << method;
        EXPECT_GT(vAtShadowOf(after, scene, light, centre), 0.9f) << method << ": the old shadow is gone";
        EXPECT_LT(vAtShadowOf(after, scene, light, centre + shift), 0.1f) << method << ": the shadow moved";
    }
}

// A small box moved beside a large mesh: the patches draw only the large mesh's clusters that
// reach the box's old and new place, and every method renders as a fresh scene with the box there.
TEST(SceneUpdates, APatchDrawsOnlyTheClustersOfALargeMeshThatReachTheMove) {
    const glm::vec3 light(-0.5f, 0.3f, 4.0f);
    const Mesh torus = test::makeTorus({0.8f, 0.0f, 0.6f}, 0.9f, 0.3f, 96, 48, kBoth);
    ASSERT_GT(torus.triangles.size(), 8 * size_t(GpuMesh::kClusterTriangles));
    const glm::vec3 centre(-2.2f, -1.0f, 0.5f);
    const glm::mat4 move = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.6f, 0.0f));
    auto build = [&](const glm::mat4& boxPlace) {
        Scene s;
        s.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
        s.addMesh(torus);
        Mesh box = test::makeBox(centre - glm::vec3(0.15f), centre + glm::vec3(0.15f), kBoth);
        for (glm::vec3& p : box.objectPositions) p = glm::vec3(boxPlace * glm::vec4(p, 1.0f));
        s.addMesh(box);
        s.addLight(test::makeDiskLight(light, 0.6f, "Key"));
        s.setCamera(test::makeTopCamera(96, 72));
        return s;
    };
    Scene scene = build(glm::mat4(1.0f));
    Renderer renderer(SS_BACKEND_AUTO);
    for (const std::string& method : glMethods()) renderer.render(scene, 0, method, RenderSettings{}, nullptr);
    const Renderer::CacheStats before = renderer.cacheStats();

    scene.setMeshTransform(2, move);
    expectSameAsFresh(renderer, scene, build(move));
    const Renderer::CacheStats after = renderer.cacheStats();
    const int patches = (after.cameraPassesPatched - before.cameraPassesPatched) +
                        (after.shadowMapsPatched - before.shadowMapsPatched);
    ASSERT_GT(patches, 0);
    // Each patch drew the ground, the box and at most a few of the torus's clusters.
    EXPECT_LT(after.patchTriangles - before.patchTriangles, size_t(patches) * torus.triangles.size() / 4)
        << patches << " patches";
}

TEST(SceneUpdates, ACameraChangeKeepsTheShadowMapsAndTheMeshes) {
    Scene scene = threeMeshTwoLights();
    Renderer renderer(SS_BACKEND_AUTO);
    renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    Camera c = test::makeTopCamera(80, 60);
    scene.setCamera(c);
    renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    Renderer::CacheStats s = renderer.cacheStats();
    EXPECT_EQ(s.meshUploads, 3);
    EXPECT_EQ(s.cameraPasses, 2);
    EXPECT_EQ(s.shadowMaps, 1);
}

TEST(SceneUpdates, RemovalRendersAsASceneBuiltWithoutIt) {
    Scene scene = threeMeshTwoLights();
    Renderer renderer(SS_BACKEND_AUTO);
    renderer.render(scene, 1, "shadow_map", RenderSettings{}, nullptr);
    scene.removeMesh(1);
    scene.removeLight(0);
    renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    EXPECT_EQ(renderer.cacheStats().meshUploads, 3);  // the two meshes left were kept

    Scene fresh;
    fresh.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
    fresh.addMesh(boxB());
    fresh.addLight(test::makeDiskLight({-1.0f, 0.5f, 3.0f}, 0.5f, "B"));
    fresh.setCamera(test::makeTopCamera(64, 48));
    expectSameAsFresh(renderer, scene, fresh);
}

// The add-on's two preview scenes (coarse and full size) and its render_passes scene share one
// context.
TEST(SceneUpdates, ThreeScenesRenderedInTurnKeepTheirCaches) {
    Scene coarse = threeMeshTwoLights();
    Scene preview = threeMeshTwoLights();
    Scene render = threeMeshTwoLights();
    Renderer renderer(SS_BACKEND_AUTO);
    renderer.render(coarse, 0, "shadow_map", RenderSettings{}, nullptr);
    renderer.render(preview, 0, "shadow_map", RenderSettings{}, nullptr);
    renderer.render(render, 0, "shadow_map", RenderSettings{}, nullptr);
    Renderer::CacheStats first = renderer.cacheStats();
    for (int i = 0; i < 3; ++i) {
        renderer.render(coarse, 0, "shadow_map", RenderSettings{}, nullptr);
        renderer.render(preview, 0, "shadow_map", RenderSettings{}, nullptr);
        renderer.render(render, 0, "shadow_map", RenderSettings{}, nullptr);
    }
    Renderer::CacheStats s = renderer.cacheStats();
    EXPECT_EQ(s.sceneCaches, 3);
    EXPECT_EQ(s.meshUploads, first.meshUploads);
    EXPECT_EQ(s.shadowMaps, first.shadowMaps);
    EXPECT_EQ(s.cameraPasses, first.cameraPasses);

    // A fourth scene evicts the least recently rendered one.
    Scene fourth = threeMeshTwoLights();
    renderer.render(fourth, 0, "shadow_map", RenderSettings{}, nullptr);
    renderer.render(render, 0, "shadow_map", RenderSettings{}, nullptr);
    EXPECT_EQ(renderer.cacheStats().sceneCaches, 4);
    renderer.render(coarse, 0, "shadow_map", RenderSettings{}, nullptr);
    EXPECT_EQ(renderer.cacheStats().sceneCaches, 5);
}

TEST(SceneUpdates, ARefusedEditLeavesTheSceneAsItWas) {
    Scene scene = threeMeshTwoLights();
    const uint64_t revision = scene.revision(), version = scene.meshes()[1].version;
    const auto positions = scene.meshes()[1].positions;
    glm::mat4 bad(1.0f);
    bad[3][0] = NAN;
    EXPECT_THROW(scene.setMeshTransform(1, bad), Error);
    EXPECT_THROW(scene.setMeshTransform(3, glm::mat4(1.0f)), Error);
    EXPECT_THROW(scene.updateMesh(-1, boxB()), Error);
    EXPECT_THROW(scene.removeLight(2), Error);
    Light dup = test::makeDiskLight({0, 0, 3}, 1.0f, "A");
    EXPECT_THROW(scene.updateLight(1, dup), Error);  // two lights named A
    EXPECT_EQ(scene.revision(), revision);
    EXPECT_EQ(scene.meshes()[1].version, version);
    EXPECT_EQ(scene.meshes()[1].positions, positions);
    EXPECT_EQ(scene.lights()[1].name, "B");
}

// One Embree BVH per scene geometry: the reference, refinement and the sparse check share it, a
// light or camera edit keeps it, a mesh edit rebuilds it once.
TEST(SceneUpdates, OneBvhServesReferenceRefineAndTheCheckUntilAMeshEdit) {
    Scene scene = threeMeshTwoLights();
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings fixed;
    fixed.samples = 4;
    RenderSettings adaptive = fixed;
    adaptive.options["adaptive"] = "on";
    RenderSettings refine;
    refine.refine = true;
    refine.options["refine_samples"] = "16";
    RenderSettings estimate;
    estimate.options["estimate_rmse"] = "1";
    EXPECT_EQ(renderer.cacheStats().traceSceneBuilds, 0);
    renderer.render(scene, 0, "reference", fixed, nullptr);
    EXPECT_EQ(renderer.cacheStats().traceSceneBuilds, 1);
    renderer.render(scene, 1, "reference", adaptive, nullptr);
    Layers refined = renderer.render(scene, 0, "pcss", refine, nullptr);
    double rmse = 0.0;
    renderer.render(scene, 0, "shadow_map", estimate, nullptr, &rmse);
    EXPECT_TRUE(std::isfinite(rmse));  // the sparse check ran, on the same BVH
    EXPECT_EQ(renderer.cacheStats().traceSceneBuilds, 1);

    scene.updateLight(1, test::makeDiskLight({-0.6f, 0.9f, 3.2f}, 0.7f, "B"));
    scene.setCamera(test::makeTopCamera(64, 48));
    renderer.render(scene, 1, "reference", fixed, nullptr);
    renderer.render(scene, 0, "pcss", refine, nullptr);
    EXPECT_EQ(renderer.cacheStats().traceSceneBuilds, 1);  // lights and camera are not in the BVH

    scene.updateMesh(2, boxBEdited());
    Layers edited = renderer.render(scene, 0, "pcss", refine, nullptr);
    renderer.render(scene, 0, "reference", fixed, nullptr);
    renderer.render(scene, 0, "shadow_map", estimate, nullptr, &rmse);
    EXPECT_EQ(renderer.cacheStats().traceSceneBuilds, 2);

    // The rebuilt BVH traces the edited geometry: refine matches a fresh renderer's on a scene
    // built with the edit.
    Scene fresh;
    fresh.addMesh(test::makeGround(4.0f, 0.0f, kBoth));
    fresh.addMesh(boxA());
    fresh.addMesh(boxBEdited());
    fresh.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f, "A"));
    fresh.addLight(test::makeDiskLight({-0.6f, 0.9f, 3.2f}, 0.7f, "B"));
    fresh.setCamera(test::makeTopCamera(64, 48));
    Renderer cold(SS_BACKEND_AUTO);
    EXPECT_EQ(edited.find("V")->pixels, cold.render(fresh, 0, "pcss", refine, nullptr).find("V")->pixels);
    EXPECT_NE(edited.find("V")->pixels, refined.find("V")->pixels);
}

// Every cache counter by name, read through the C API.
std::map<std::string, double> capiCacheStats(const ss_context* context) {
    std::map<std::string, double> stats;
    for (int32_t i = 0; i < ss_cache_stat_count(); ++i) {
        double value = -1.0;
        EXPECT_EQ(ss_context_cache_stat(context, ss_cache_stat_name(i), &value), SS_OK) << ss_last_error();
        stats[ss_cache_stat_name(i)] = value;
    }
    return stats;
}

// The same through the C API, counted by ss_context_cache_stat.
TEST(SceneUpdates, TheCApiUpdatesOneMeshAndCountsUploads) {
    ss_scene* scene = nullptr;
    ASSERT_EQ(ss_scene_create(&scene), SS_OK);
    for (const Mesh& m : {test::makeGround(4.0f, 0.0f, kBoth), boxA(), boxB()})
        ASSERT_EQ(addMeshThroughCApi(scene, m, nullptr), SS_OK);
    const ss_light_desc light = lightADesc();
    ASSERT_EQ(ss_scene_add_light(scene, &light, nullptr), SS_OK);
    const ss_camera_desc camera = topCameraDesc();
    ASSERT_EQ(ss_scene_set_camera(scene, &camera), SS_OK);

    ss_context* context = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &context), SS_OK);
    ss_result* result = nullptr;
    ASSERT_EQ(ss_render(context, scene, 0, "shadow_map", nullptr, &result), SS_OK);
    ss_result_destroy(result);
    float move[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.3f, 0.1f, 0, 1};
    ASSERT_EQ(ss_scene_set_mesh_transform(scene, 2, move), SS_OK);
    ASSERT_EQ(ss_render(context, scene, 0, "shadow_map", nullptr, &result), SS_OK);
    ss_result_destroy(result);
    std::map<std::string, double> stats = capiCacheStats(context);
    EXPECT_EQ(stats.at("frames"), 1);
    EXPECT_EQ(stats.at("mesh_uploads"), 3);  // a move sends a matrix, no vertex
    EXPECT_EQ(stats.at("shadow_maps"), 2);
    std::vector<float> xyz;
    for (const glm::vec3& p : boxBEdited().objectPositions) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    ASSERT_EQ(ss_scene_update_mesh(scene, 2, xyz.data(), uint32_t(xyz.size() / 3), &boxBEdited().triangles[0][0],
                                   uint32_t(boxBEdited().triangles.size()), kBoth),
              SS_OK);
    ASSERT_EQ(ss_render(context, scene, 0, "shadow_map", nullptr, &result), SS_OK);
    ss_result_destroy(result);
    stats = capiCacheStats(context);
    EXPECT_EQ(stats.at("mesh_uploads"), 4);  // new geometry is uploaded, the other meshes are not
    // The stage times: each shared pass drawn took time, and the method runs contain them.
    EXPECT_GT(stats.at("camera_pass_ms"), 0.0);
    EXPECT_GT(stats.at("shadow_map_ms"), 0.0);
    EXPECT_GT(stats.at("upload_ms"), 0.0);
    EXPECT_GE(stats.at("method_ms"), stats.at("camera_pass_ms") + stats.at("shadow_map_ms") + stats.at("upload_ms"));
    EXPECT_EQ(stats.at("trace_scene_builds"), 0);  // GL methods alone trace nothing
    ss_render_options options;
    ss_render_options_default(&options);
    options.samples = 4;
    for (int i = 0; i < 2; ++i) {
        ASSERT_EQ(ss_render(context, scene, 0, "reference", &options, &result), SS_OK);
        ss_result_destroy(result);
    }
    options.settings = "refine_samples=16";
    options.refine = SS_REFINE_ON;
    ASSERT_EQ(ss_render(context, scene, 0, "pcss", &options, &result), SS_OK);
    ss_result_destroy(result);
    stats = capiCacheStats(context);
    EXPECT_EQ(stats.at("trace_scene_builds"), 1);
    const double meshBvhs = stats.at("mesh_bvh_builds");
    EXPECT_EQ(meshBvhs, 3);  // one per mesh
    ASSERT_EQ(ss_scene_set_mesh_transform(scene, 1, move), SS_OK);
    ASSERT_EQ(ss_render(context, scene, 0, "pcss", &options, &result), SS_OK);
    ss_result_destroy(result);
    stats = capiCacheStats(context);
    EXPECT_EQ(stats.at("trace_scene_builds"), 2);
    EXPECT_EQ(stats.at("mesh_bvh_builds"), meshBvhs);  // a move keeps every mesh's BVH
    EXPECT_EQ(ss_scene_update_light(scene, 1, &light), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ss_last_error()).find("light index 1"), std::string::npos);
    EXPECT_EQ(ss_scene_remove_mesh(scene, 3), SS_ERROR_INVALID_ARGUMENT);
    ss_context_destroy(context);
    ss_scene_destroy(scene);
}


// One mesh model through the C API: a mesh added with its matrix is the mesh added at the
// identity and moved there, and a scene file keeps it; each renders the same pixels, bit for bit.
// A matrix the mesh cannot be placed by is refused naming the mesh, and nothing is added.
TEST(SceneUpdates, AMeshAddedWithItsMatrixIsTheMovedMeshAndItsSavedFile) {
    const glm::mat4 place = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -0.2f, 0.4f)), 0.7f,
                                                   glm::normalize(glm::vec3(0.2f, 1.0f, 0.5f))),
                                       glm::vec3(1.3f, 0.6f, 0.9f));
    auto build = [&](bool matrixFirst) {
        ss_scene* scene = nullptr;
        EXPECT_EQ(ss_scene_create(&scene), SS_OK);
        EXPECT_EQ(addMeshThroughCApi(scene, test::makeGround(4.0f, 0.0f, kBoth), nullptr), SS_OK);
        EXPECT_EQ(addMeshThroughCApi(scene, boxA(), matrixFirst ? &place[0][0] : nullptr), SS_OK);
        if (!matrixFirst) {
            EXPECT_EQ(ss_scene_set_mesh_transform(scene, 1, &place[0][0]), SS_OK);
        }
        const ss_light_desc light = lightADesc();
        EXPECT_EQ(ss_scene_add_light(scene, &light, nullptr), SS_OK);
        const ss_camera_desc camera = topCameraDesc();
        EXPECT_EQ(ss_scene_set_camera(scene, &camera), SS_OK);
        return scene;
    };
    ss_context* context = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &context), SS_OK);
    auto visibility = [&](const ss_scene* scene, const char* method) {
        ss_render_options options;
        ss_render_options_default(&options);
        options.samples = 8;
        ss_result* result = nullptr;
        EXPECT_EQ(ss_render(context, scene, 0, method, &options, &result), SS_OK) << ss_last_error();
        const float* px = nullptr;
        int32_t w = 0, h = 0;
        EXPECT_EQ(ss_result_layer(result, 0, nullptr, &px, &w, &h), SS_OK);
        std::vector<float> v(px, px + size_t(w) * size_t(h));
        ss_result_destroy(result);
        return v;
    };
    ss_scene* given = build(true);
    ss_scene* moved = build(false);
    const std::string file = testing::TempDir() + "ss_matrix_scene.json";
    ASSERT_EQ(ss_scene_save(given, file.c_str()), SS_OK);
    ss_scene* loaded = nullptr;
    ASSERT_EQ(ss_scene_load(file.c_str(), &loaded), SS_OK) << ss_last_error();
    std::remove(file.c_str());
    ss_scene* atIdentity = build(false);
    const glm::mat4 identity(1.0f);
    ASSERT_EQ(ss_scene_set_mesh_transform(atIdentity, 1, &identity[0][0]), SS_OK);
    for (const char* method : {"shadow_map", "reference"}) {
        const std::vector<float> v = visibility(given, method);
        EXPECT_EQ(v, visibility(moved, method)) << method;
        EXPECT_EQ(v, visibility(loaded, method)) << method;
        EXPECT_NE(v, visibility(atIdentity, method)) << method << ": the matrix moves the shadow";
    }

    glm::mat4 projective = place;
    projective[0][3] = 0.25f;
    glm::mat4 notFinite = place;
    notFinite[3][1] = std::numeric_limits<float>::quiet_NaN();
    for (const glm::mat4& bad : {projective, notFinite}) {
        EXPECT_EQ(addMeshThroughCApi(given, boxB(), &bad[0][0], "Refused"), SS_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(ss_last_error()).find("mesh 'Refused'"), std::string::npos) << ss_last_error();
        EXPECT_EQ(ss_scene_mesh_count(given), 2);
        EXPECT_EQ(ss_scene_set_mesh_transform(given, 1, &bad[0][0]), SS_ERROR_INVALID_ARGUMENT);
    }
    EXPECT_EQ(visibility(given, "shadow_map"), visibility(moved, "shadow_map")) << "a refused move moves nothing";
    for (ss_scene* s : {given, moved, loaded, atIdentity}) ss_scene_destroy(s);
    ss_context_destroy(context);
}


// A method's prepared geometry (sweep's shadow mesh, penumbra_map's cones and sheets) depends on
// the meshes and its light only: a camera edit and another light's edit keep it, a move rebuilds
// it, and what is rendered with the kept geometry equals a fresh renderer's image.
TEST(SceneUpdates, PreparedGeometrySurvivesCameraAndOtherLightEdits) {
    const std::pair<const char*, const char*> cases[] = {{"sweep", "sweep: geometry"},
                                                         {"penumbra_map", "penumbra_map cones and sheets"}};
    for (const auto& [method, stage] : cases) {
        SCOPED_TRACE(method);
        Scene scene = threeMeshTwoLights();
        Renderer renderer(SS_BACKEND_AUTO);
        int builds = 0;
        RenderSettings settings;
        settings.progress = [&, stage = std::string(stage)](float, const char* s) {
            if (stage == s) ++builds;
            return true;
        };
        renderer.render(scene, 0, method, settings, nullptr);
        EXPECT_EQ(builds, 1);

        scene.setCamera(test::makeTopCamera(80, 60));
        Layers afterCamera = renderer.render(scene, 0, method, settings, nullptr);
        EXPECT_EQ(builds, 1) << "a camera edit rebuilt the geometry";
        Renderer fresh(SS_BACKEND_AUTO);
        EXPECT_EQ(afterCamera.find("V")->pixels, fresh.render(scene, 0, method, RenderSettings{}, nullptr).find("V")->pixels);

        Light other = scene.light(1);
        other.size *= 1.5f;
        scene.updateLight(1, other);
        renderer.render(scene, 0, method, settings, nullptr);
        EXPECT_EQ(builds, 1) << "another light's edit rebuilt the geometry";

        Light own = scene.light(0);
        own.size *= 1.5f;
        scene.updateLight(0, own);
        renderer.render(scene, 0, method, settings, nullptr);
        EXPECT_EQ(builds, 2) << "the light's own edit kept stale geometry";

        scene.setMeshTransform(1, glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.2f, 0.0f)));
        Layers afterMove = renderer.render(scene, 0, method, settings, nullptr);
        EXPECT_EQ(builds, 3) << "a move kept stale geometry";
        Renderer fresh2(SS_BACKEND_AUTO);
        EXPECT_EQ(afterMove.find("V")->pixels, fresh2.render(scene, 0, method, RenderSettings{}, nullptr).find("V")->pixels);
    }
}

}  // namespace
}  // namespace ss
