// Does occlusion_textures hold under a tilted rectangle light over a large ground? The slices
// are parallel to the light, so a tilted light sees the ground across its whole depth range; a
// ground that cannot shadow anything is left out of the slices, which then span the occluder.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "io/metrics.h"
#include "methods/occlusion_textures/slicing.h"
#include "renderer/renderer.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::layer;
using test::run;

// A pillar (0.5 x 0.5 x 2 m) standing on a 200 m ground, under a 3 x 1.5 m rectangle light 3 m
// from the pillar's middle, tilted `tilt` degrees from facing down and turned `spin` about its
// own normal. Only the ground receives (the pillar's own faces are another limit).
Scene tiltedScene(float tilt, float spin) {
    Scene s;
    s.addMesh(test::makeGround(100.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(test::makeBox({-0.25f, -0.25f, 0.0f}, {0.25f, 0.25f, 2.0f}, SS_MESH_CAST));
    Light light = test::makeDiskLight({0.0f, 0.0f, 0.0f}, 3.0f, "Tilted");
    light.type = LightType::Rectangle;
    light.sizeY = 1.5f;
    glm::mat4 m = glm::rotate(glm::mat4(1.0f), glm::radians(tilt), glm::vec3(1, 0, 0));
    m = glm::rotate(m, glm::radians(spin), glm::vec3(0, 0, 1));
    light.lightToWorld = m;
    light.lightToWorld[3] = glm::vec4(glm::vec3(0.0f, 0.0f, 1.0f) - 3.0f * light.direction(), 1.0f);
    s.addLight(light);
    s.setCamera(test::makeTopCamera(320, 240));
    return s;
}

Renderer& renderer() {
    static Renderer r(SS_BACKEND_AUTO);
    return r;
}

// The tilted light's ground is left out of the slices and the slices span the pillar's depths only; a mesh
// below the ground's plane keeps the ground in (it could shadow that mesh).
TEST(OcclusionTexturesTilted, AGroundThatCannotShadowIsNotSliced) {
    Scene scene = tiltedScene(45.0f, 30.0f);
    occlusion::KernelLight kernel = occlusion::kernelLight(scene.light(0), scene.bounds());
    occlusion::SliceSetup setup = occlusion::fitSlices(scene, kernel, 8, 512, occlusion::Projection::Perspective, 0);
    EXPECT_EQ(setup.unsliced, std::vector<int>{0});
    EXPECT_FALSE(setup.sliced(0));
    EXPECT_TRUE(setup.sliced(1));
    float lo = 1e30f, hi = -1e30f;
    for (const glm::vec3& p : scene.meshes()[1].positions) {
        lo = std::min(lo, kernel.toLocal(p).z);
        hi = std::max(hi, kernel.toLocal(p).z);
    }
    EXPECT_NEAR(setup.planes.front(), lo, 1e-4f);
    EXPECT_NEAR(setup.planes.back(), hi, 1e-4f);

    Scene below = tiltedScene(45.0f, 30.0f);
    below.addMesh(test::makeBox({3.0f, 3.0f, -1.0f}, {3.5f, 3.5f, -0.5f}, SS_MESH_CAST | SS_MESH_RECEIVE));
    occlusion::SliceSetup kept = occlusion::fitSlices(below, kernel, 8, 512, occlusion::Projection::Perspective, 0);
    EXPECT_TRUE(kept.unsliced.empty());

    // Under a light facing straight down the ground is parallel to it, at the bottom of the
    // range: it stays sliced, as the method has always had it.
    Scene straight = tiltedScene(0.0f, 0.0f);
    occlusion::SliceSetup down = occlusion::fitSlices(
        straight, occlusion::kernelLight(straight.light(0), straight.bounds()), 8, 512, occlusion::Projection::Perspective, 0);
    EXPECT_TRUE(down.unsliced.empty());
}

// Measured (reference 256 samples), receivers RMSE with the ground sliced / left out:
// tilt 30 0.080 / 0.041, 45 0.108 / 0.044, 60 0.125 / 0.047 (spin 30); straight down 0.0122
// either way (the ground is parallel to the light, in the last slice).
TEST(OcclusionTexturesTilted, TiltedRectangleLightOverALargeGroundAgainstTheReference) {
    const int refSamples = test::quickTests() ? 64 : 256;
    struct Case {
        float tilt, spin, bound;
    };
    for (Case c : {Case{0.0f, 0.0f, 0.02f}, Case{30.0f, 30.0f, 0.06f}, Case{45.0f, 30.0f, 0.06f},
                   Case{60.0f, 30.0f, 0.06f}, Case{60.0f, 0.0f, 0.06f}}) {
        Scene scene = tiltedScene(c.tilt, c.spin);
        Layers ref = run(renderer(), scene, "reference", refSamples);
        Layers ot = run(renderer(), scene, "occlusion_textures", 0);
        const Image& rm = layer(ref, "mask");
        const Image& om = layer(ot, "mask");
        Image mask(rm.width, rm.height, 0.0f);
        for (size_t i = 0; i < mask.pixels.size(); ++i) mask.pixels[i] = rm.pixels[i] > 0.5f && om.pixels[i] > 0.5f;
        Metrics m = compareVisibility(layer(ot, "V"), layer(ref, "V"), &mask);
        std::printf("tilt %.0f spin %.0f: %s\n", c.tilt, c.spin, m.toString().c_str());
        EXPECT_GT(m.pixels, 70000u);
        EXPECT_LT(m.rmse, c.bound) << "tilt " << c.tilt << " spin " << c.spin << ": " << m.toString();
    }
}

}  // namespace
}  // namespace ss
