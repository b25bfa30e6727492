// Checks how close the hard shadow map comes to the reference on the built-in example scene.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cstdlib>

#include "io/metrics.h"
#include "io/scene_file.h"
#include "renderer/renderer.h"

namespace ss {
namespace {

TEST(ShadowMapExample, UmbraAndLitRegionsOverlapTheReference) {
    // Half resolution keeps the reference quick; the projection is unchanged (same aspect).
    Scene file = loadSceneFile(SS_SOURCE_DIR "/examples/scenes/demo.json");
    Scene scene;
    for (const Mesh& m : file.meshes()) scene.addMesh(m);
    for (const Light& l : file.lights()) scene.addLight(l);
    Camera camera = file.camera();
    camera.width /= 2;
    camera.height /= 2;
    scene.setCamera(camera);

    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings refSettings;
    refSettings.samples = std::getenv("SS_TEST_QUICK") ? 64 : 256;
    std::string used;
    Layers ref = renderer.render(scene, 0, "reference", refSettings, &used);
    Layers hard = renderer.render(scene, 0, "shadow_map", RenderSettings{}, &used);
    Image mask = *ref.find("mask");
    const Image& hardMask = *hard.find("mask");
    for (size_t i = 0; i < mask.pixels.size(); ++i) mask.pixels[i] *= hardMask.pixels[i];
    Metrics m = compareVisibility(*ref.find("V"), *hard.find("V"), &mask);
    std::printf("shadow_map vs reference on the example: rmse %.4f umbra IoU %.3f lit IoU %.3f\n",
                m.rmse, m.umbraIoU, m.litIoU);
    // A hard shadow from the light centre cuts every penumbra near its middle, so its
    // "umbra" is the true umbra plus the inner half of the penumbra and its lit region the
    // true lit region plus the outer half. With this light (1.5 m disk, occluders 1-2 m above
    // the ground) the penumbra is about as wide as the umbra, which bounds umbra IoU near
    // 1/(1+0.5·1) ≈ 0.6; measured 0.50 at 640x480. The lit region dwarfs the penumbra, so its
    // IoU stays high (measured 0.97). The bounds leave room for sampling noise and resolution.
    EXPECT_GT(m.umbraIoU, 0.40);
    EXPECT_LT(m.umbraIoU, 0.75);  // higher would mean the reference lost its penumbra
    EXPECT_GT(m.litIoU, 0.94);
    EXPECT_LT(m.rmse, 0.10);
    EXPECT_GT(m.rmse, 0.03);  // a hard shadow cannot match a soft one
}

}  // namespace
}  // namespace ss
