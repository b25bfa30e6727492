// Does the camera see past a mesh hidden from it (SS_MESH_CAMERA_HIDDEN) while it still casts, in
// the reference and the GL methods alike, and does the scene file keep the flag?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/scene.h"
#include "io/scene_file.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

// A ground, and a plate above it that shadows the ground right below it (light straight above).
Scene plateScene(uint32_t plateFlags) {
    Scene scene;
    scene.addMesh(test::makeGround(6.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addMesh(test::makeBox({-1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 1.1f}, plateFlags));
    scene.addLight(test::makeDiskLight({0.0f, 0.0f, 5.0f}, 0.5f));
    scene.setCamera(test::makeTopCamera(96, 72));
    return scene;
}

struct Probe {
    float v, mask;
};

Probe centre(Renderer& renderer, const Scene& scene, const std::string& method) {
    RenderSettings settings;
    settings.samples = 16;
    Layers layers = renderer.render(scene, 0, method, settings, nullptr);
    const Image* v = layers.find("V");
    const Image* mask = layers.find("mask");
    if (!v || !mask) throw std::runtime_error("missing layer");
    glm::vec2 p = scene.camera().worldToPixel({0.0f, 0.0f, 1.1f});  // the plate's top centre
    return {v->at(int(p.x), int(p.y)), mask->at(int(p.x), int(p.y))};
}

TEST(CameraHidden, TheCameraSeesTheShadowBehindAHiddenCaster) {
    Renderer renderer(SS_BACKEND_AUTO);
    const Scene seen = plateScene(SS_MESH_CAST);
    const Scene hidden = plateScene(SS_MESH_CAST | SS_MESH_CAMERA_HIDDEN);
    for (const char* method : {"reference", "shadow_map", "pcss"}) {
        // Seen, the plate is what the pixel shows: not a receiver, outside the mask, V = 1.
        Probe a = centre(renderer, seen, method);
        EXPECT_EQ(a.mask, 0.0f) << method;
        EXPECT_EQ(a.v, 1.0f) << method;
        // Hidden, the pixel shows the ground in the plate's umbra: the plate still casts.
        Probe b = centre(renderer, hidden, method);
        EXPECT_EQ(b.mask, 1.0f) << method;
        EXPECT_LT(b.v, 0.05f) << method;
    }
}

TEST(CameraHidden, TheFlagGoesThroughTheCApiAndTheSceneFile) {
    ss_scene* scene = nullptr;
    ASSERT_EQ(ss_scene_create(&scene), SS_OK);
    const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t tri[] = {0, 1, 2};
    EXPECT_EQ(ss_scene_add_mesh(scene, "hidden", xyz, 3, tri, 1, nullptr, SS_MESH_CAST | SS_MESH_CAMERA_HIDDEN, nullptr),
              SS_OK)
        << ss_last_error();
    EXPECT_NE(ss_scene_add_mesh(scene, "odd", xyz, 3, tri, 1, nullptr, 16u, nullptr), SS_OK);
    ss_scene_destroy(scene);

    Scene original = plateScene(SS_MESH_CAST | SS_MESH_CAMERA_HIDDEN);
    const std::string path = ::testing::TempDir() + "camera_hidden_scene.json";
    saveSceneFile(original, path);
    Scene loaded = loadSceneFile(path);
    ASSERT_EQ(loaded.meshes().size(), 2u);
    EXPECT_EQ(loaded.meshes()[1].flags, SS_MESH_CAST | SS_MESH_CAMERA_HIDDEN);
    EXPECT_EQ(loaded.meshes()[0].flags, SS_MESH_CAST | SS_MESH_RECEIVE);
}

}  // namespace
}  // namespace ss
