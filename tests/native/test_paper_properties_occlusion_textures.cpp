// Does occlusion_textures keep the paper's claims: perspective slicing leaks less light than
// orthographic (figure 4), kernels never jut out of the slice (figure 5), and a quality that
// does not depend on the light's size?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/light.h"
#include "methods/occlusion_textures/slicing.h"
#include "softshadow/softshadow.h"
#include "test_pcss_support.h"

namespace ss::test {
namespace {

// Figure 5: the slicing camera's frustum passes through the light's edges, so the light seen
// from any point P inside it, cut by a slice plane above P, lies inside the frustum too: no
// kernel reads outside its slice's texture. Checked on the CPU mirror of the shader's lookup
// for a grid of points over the whole ground and on the occluder's top, every slice above them.
TEST(PaperPropertiesOcclusionTextures, Figure5KernelsStayInsideTheSlicesFrustum) {
    for (float diameter : {0.5f, 1.5f, 3.0f}) {
        SceneParams p;
        p.lightDiameter = diameter;
        Scene scene = sceneBox(p);
        occlusion::KernelLight kl = occlusion::kernelLight(scene.lights()[0], scene.bounds());
        occlusion::SliceSetup setup = occlusion::fitSlices(scene, kl, 8, 512);
        size_t lookups = 0, outside = 0;
        double worst = 0.0;  // the largest overshoot past the texture's edge, in texels
        for (float z : {0.0f, 1.2f})
            for (int iy = 0; iy <= 40; ++iy)
                for (int ix = 0; ix <= 40; ++ix) {
                    float half = z == 0.0f ? 8.0f : 0.6f;
                    glm::vec3 world(-half + 2 * half * ix / 40.0f, -half + 2 * half * iy / 40.0f, z);
                    glm::vec3 local = kl.toLocal(world);
                    for (int k = 0; k < setup.count(); ++k) {
                        if (setup.planes[size_t(k) + 1] >= local.z) continue;  // slices above P only
                        occlusion::SliceLookup l = occlusion::lookupSlice(setup, local, k, occlusion::Fade::Below);
                        glm::vec2 c = l.uv * glm::vec2(setup.width, setup.height);
                        glm::vec2 lo = c - 0.5f * l.kernelTexels, hi = c + 0.5f * l.kernelTexels;
                        double over = std::max({-double(lo.x), -double(lo.y), double(hi.x) - setup.width,
                                                double(hi.y) - setup.height, 0.0});
                        worst = std::max(worst, over);
                        outside += over > 1e-2;
                        ++lookups;
                    }
                }
        std::printf("[occlusion_textures] figure 5, D %.2f: d %.3f, %zu kernels, %zu outside, worst %.2g texels\n",
                    diameter, setup.d, lookups, outside, worst);
        EXPECT_GT(lookups, 1000u);
        EXPECT_EQ(outside, 0u) << "D " << diameter << ": worst overshoot " << worst << " texels";
    }
}

// The paper claims the quality does not depend on the light's size (the kernel grows, the
// pre-filtered lookup costs the same). Measured against the reference on the box scene with a
// square light (the method's own shape, so no shape substitution enters the error).
TEST(PaperPropertiesOcclusionTextures, LightSizeIndependence) {
    std::vector<Metrics> m, inPenumbra;
    for (float size : {0.75f, 2.0f}) {
        Scene scene = sceneBox();
        Light light = scene.lights()[0];
        light.type = LightType::Square;
        light.size = size;
        Scene s2;
        for (const Mesh& mesh : scene.meshes()) s2.addMesh(mesh);
        s2.addLight(light);
        s2.setCamera(scene.camera());
        Layers ot = renderWith(s2, "occlusion_textures");
        Layers ref = renderReference(s2);
        m.push_back(compareToReference(ot, ref));
        // The error where the reference is in penumbra: the image RMSE grows with the penumbra's
        // area alone, this one measures the quality of the penumbra itself.
        Image pen = *ref.find("mask");
        const Image& vref = *ref.find("V");
        for (size_t i = 0; i < pen.pixels.size(); ++i)
            pen.pixels[i] = pen.pixels[i] > 0.5f && vref.pixels[i] > 0.05f && vref.pixels[i] < 0.95f ? 1.0f : 0.0f;
        inPenumbra.push_back(compareVisibility(*ot.find("V"), vref, &pen));
        std::printf("[occlusion_textures] square light %.2f m: %s\n  in the reference's penumbra: %s\n", size,
                    m.back().toString().c_str(), inPenumbra.back().toString().c_str());
    }
    // Measured (512² textures, 8 slices, sat): image RMSE 0.020 (0.75 m) and 0.036 (2 m), umbra
    // IoU 0.67 and 0.42; in the reference's penumbra (449 and 973 px) RMSE 0.130 and 0.159, mean
    // |error| 0.114 and 0.126. So the claim holds only roughly: a light 2.7x larger doubles the
    // penumbra's area but its per-pixel error grows by about a fifth; the image error grows
    // with the penumbra's area and the umbra's boundary gets worse.
    for (const Metrics& x : m) EXPECT_LT(x.rmse, 0.05) << x.toString();
    for (const Metrics& x : inPenumbra) EXPECT_LT(x.rmse, 0.2) << x.toString();
    EXPECT_GT(double(inPenumbra[1].pixels), 1.8 * double(inPenumbra[0].pixels)) << "the penumbra must grow";
    EXPECT_LT(inPenumbra[1].rmse, 1.35 * inPenumbra[0].rmse)
        << inPenumbra[0].toString() << " / " << inPenumbra[1].toString();
}

// Figure 4's scene: a thin plate tilted through several slices under a small square light. An
// orthographic slicing camera cuts the plate into patches stored straight below each piece;
// the lookup follows the line from the light centre, which passes between the patches: light
// leaks in stripes across the plate's shadow. The perspective camera (COP just behind the
// light) stores each piece close to where those lines cross it.
Scene tiltedThinPlate() {
    Scene s;
    s.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    Mesh plate = makeBox({-1.2f, -0.6f, -0.01f}, {1.2f, 0.6f, 0.01f}, SS_MESH_CAST);
    for (glm::vec3& p : plate.objectPositions) p.z += 1.5f + 0.5f * p.x;  // 0.9 .. 2.1 above the ground
    plate.finalize();
    s.addMesh(plate);
    Light light = makeDiskLight({0.3f, 0.2f, 4.0f}, 0.5f);
    light.type = LightType::Square;
    s.addLight(light);
    s.setCamera(makeTopCamera());
    return s;
}

TEST(PaperPropertiesOcclusionTextures, Figure4PerspectiveSlicingLeaksLessThanOrthographic) {
    Scene scene = tiltedThinPlate();
    Layers ref = renderReference(scene);
    const Image& vref = *ref.find("V");
    const Image& mask = *ref.find("mask");
    struct Result {
        Metrics image;
        size_t leaks = 0;  // lit (V > 0.5) where the reference is in umbra (V < 0.1)
    };
    auto measure = [&](const char* slicing, const char* resolution) {
        Layers ot = renderWith(scene, "occlusion_textures", {{"slicing", slicing}, {"resolution", resolution}});
        dumpPng(std::string("figure4_") + slicing + "_" + resolution, *ot.find("V"));
        Result r;
        r.image = compareToReference(ot, ref);
        const Image& v = *ot.find("V");
        for (size_t i = 0; i < v.pixels.size(); ++i)
            r.leaks += mask.pixels[i] > 0.5f && vref.pixels[i] < 0.1f && v.pixels[i] > 0.5f;
        std::printf("[occlusion_textures] figure 4, slicing=%s resolution=%s: %zu px leak (lit where the reference "
                    "is umbra); %s\n",
                    slicing, resolution, r.leaks, r.image.toString().c_str());
        return r;
    };
    dumpPng("figure4_reference", vref);
    Result perspective = measure("perspective", "512"), orthographic = measure("orthographic", "512");
    Result sharpOrthographic = measure("orthographic", "4096");
    size_t umbra = 0;
    for (size_t i = 0; i < vref.pixels.size(); ++i) umbra += mask.pixels[i] > 0.5f && vref.pixels[i] < 0.1f;
    ASSERT_GT(umbra, 300u) << "the plate must cast an umbra";
    // Measured (160 x 120, 8 slices, sat): perspective RMSE 0.018 with no leaking pixel;
    // orthographic 0.070 with 11, and still 0.074 with 10 at 4096² (eight times the texel
    // density): the leaks are the patches' misalignment, not the orthographic textures' coarser
    // texels (the paper's other objection).
    for (const Result* o : {&orthographic, &sharpOrthographic}) {
        EXPECT_LT(perspective.image.rmse, 0.5 * o->image.rmse);
        EXPECT_GE(o->leaks, 5u);
        EXPECT_LT(2 * perspective.leaks, o->leaks);
    }
}

TEST(PaperPropertiesOcclusionTextures, SlicingSettingIsChecked) {
    expectSettingRefused(tiltedThinPlate(), "occlusion_textures", {{"slicing", "fisheye"}}, "slicing");
}

}  // namespace
}  // namespace ss::test
