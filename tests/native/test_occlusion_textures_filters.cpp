// Checks the CPU reference box filters of occlusion_textures: SAT and N-Buffers against brute force.
// SPDX-License-Identifier: GPL-3.0-or-later
// Mipmaps within a stated tolerance of the SAT, and the slicing geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "filters/box_filter.h"
#include "methods/occlusion_textures/slicing.h"

namespace ss {
namespace {

using filters::Plane;

// A binary occlusion texture with blobs and thin lines, like a slice of foliage.
Plane randomOcclusion(int w, int h, uint32_t seed) {
    Plane p(w, h);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int b = 0; b < 12; ++b) {
        float cx = u(rng) * w, cy = u(rng) * h, r = 1.0f + u(rng) * 0.15f * w;
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i)
                if ((i + 0.5f - cx) * (i + 0.5f - cx) + (j + 0.5f - cy) * (j + 0.5f - cy) < r * r) p.at(i, j) = 1.0f;
    }
    for (int j = 0; j < h; ++j) p.at((j * 7) % w, j) = 1.0f;
    return p;
}

TEST(OcclusionTexturesFilters, SatEqualsBruteForceBox) {
    Plane p = randomOcclusion(97, 64, 3);
    auto sat = filters::SummedAreaTable::build(p);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-5.0f, 102.0f), s(0.05f, 60.0f);
    double worst = 0.0;
    for (int n = 0; n < 2000; ++n) {
        float x0 = u(rng), y0 = u(rng) * 0.66f, w = s(rng), h = s(rng);
        double brute = filters::boxBrute(p, x0, y0, x0 + w, y0 + h);
        double fast = sat.box(x0, y0, x0 + w, y0 + h);
        worst = std::max(worst, std::abs(brute - fast));
    }
    // The integer corner sums are exact in float (< 2^24); what remains is one rounding of a
    // fractional weight times a strip sum of at most 97 x 64 texels, divided by the box area:
    // relative 6e-8 x 6208 / 0.0025 ~ 1e-4 at the smallest box. Stated bound: 2e-4.
    EXPECT_LT(worst, 2e-4) << "largest |SAT - brute force| over 2000 boxes";
}

TEST(OcclusionTexturesFilters, NBufferLevelIsBruteForceBoxOfTwoToTheL) {
    Plane p = randomOcclusion(64, 48, 7);
    auto nb = filters::NBuffer::build(p);
    ASSERT_EQ(nb.levels.size(), 7u);  // 1, 2, 4 ... 64
    double worst = 0.0;
    for (size_t l = 0; l < nb.levels.size(); ++l) {
        int size = 1 << l;
        for (int j = 0; j < p.height; j += 3)
            for (int i = 0; i < p.width; i += 3) {
                double brute = filters::boxBrute(p, i, j, i + size, j + size);
                worst = std::max(worst, std::abs(brute - nb.levels[l].at(i, j)));
            }
    }
    // Means of 0/1 values built by exact halvings: only float rounding of sums <= 1. Bound 1e-6.
    EXPECT_LT(worst, 1e-6);
    // Centred lookups at exact power-of-two sizes on texel corners are exact boxes too.
    for (int l = 0; l < 5; ++l) {
        float s = float(1 << l);
        EXPECT_NEAR(nb.box(20.0f, 16.0f, s, s), filters::boxBrute(p, 20 - s / 2, 16 - s / 2, 20 + s / 2, 16 + s / 2), 1e-6)
            << "level " << l;
    }
}

TEST(OcclusionTexturesFilters, MipmapWithinStatedToleranceOfSat) {
    Plane p = randomOcclusion(128, 128, 11);
    auto sat = filters::SummedAreaTable::build(p);
    auto mip = filters::Mipmap::build(p);
    auto nb = filters::NBuffer::build(p);
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> c(16.0f, 112.0f), s(2.0f, 32.0f);
    double sumMip = 0.0, sumNb = 0.0, worstMip = 0.0;
    int n = 3000;
    for (int k = 0; k < n; ++k) {
        float cx = c(rng), cy = c(rng), w = s(rng), h = w * (k % 3 == 0 ? 2.0f : 1.0f);
        float exact = sat.box(cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2);
        float m = mip.box(cx, cy, w, h), b = nb.box(cx, cy, w, h);
        sumMip += (m - exact) * (m - exact);
        sumNb += (b - exact) * (b - exact);
        worstMip = std::max(worstMip, double(std::abs(m - exact)));
    }
    double rmsMip = std::sqrt(sumMip / n), rmsNb = std::sqrt(sumNb / n);
    // Mipmaps average dyadically aligned blocks and blur with the trilinear tent, so a box can
    // be off by a good part of a block's contrast: measured RMS ~0.06; stated bound 0.10 RMS.
    // N-Buffers place boxes continuously and must be closer to the exact filter (paper, 3.2).
    EXPECT_LT(rmsMip, 0.10) << "worst " << worstMip;
    EXPECT_LT(rmsNb, rmsMip);
    std::printf("box filter RMS vs SAT: mipmap %.4f, nbuffer %.4f\n", rmsMip, rmsNb);
}

// The fitted frustum holds every vertex; the kernel of a point straight under the light centre
// is centred in the texture with the size eq. 4 gives; the fade weights ramp over one slice.
TEST(OcclusionTexturesSlicing, FrustumHoldsTheSceneAndKernelsFollowEquationFour) {
    Scene scene;
    Mesh ground;
    ground.name = "ground";
    ground.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    ground.objectPositions = {{-8, -8, 0}, {8, -8, 0}, {8, 8, 0}, {-8, 8, 0}};
    ground.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.addMesh(ground);
    Mesh plate = ground;  // a caster at height 2 so the slices span depths 2 .. 4
    plate.name = "plate";
    plate.objectPositions = {{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}};
    scene.addMesh(plate);
    Light light;
    light.name = "Area";
    light.type = LightType::Rectangle;
    light.lightToWorld = glm::mat4(1.0f);
    light.lightToWorld[3] = glm::vec4(0.0f, 0.0f, 4.0f, 1.0f);
    light.size = 2.0f;
    light.sizeY = 1.0f;
    scene.addLight(light);
    occlusion::KernelLight k = occlusion::kernelLight(light, scene.bounds());
    EXPECT_FLOAT_EQ(k.halfX, 1.0f);
    EXPECT_FLOAT_EQ(k.halfY, 0.5f);
    occlusion::SliceSetup s = occlusion::fitSlices(scene, k, 8, 512);
    EXPECT_EQ(s.width, 512);
    EXPECT_EQ(s.height, 256);  // the light's aspect: square texels
    for (const glm::vec3& p : scene.meshes()[0].positions) {
        glm::vec2 uv = occlusion::sliceUv(s, k.toLocal(p));
        EXPECT_GE(uv.x, -1e-4f);
        EXPECT_LE(uv.x, 1.0f + 1e-4f);
        EXPECT_GE(uv.y, -1e-4f);
        EXPECT_LE(uv.y, 1.0f + 1e-4f);
    }
    ASSERT_EQ(s.count(), 8);
    for (int i = 0; i < 8; ++i) EXPECT_LT(s.planes[size_t(i)], s.planes[size_t(i) + 1]);
    // A point 4 below the light, slice 0 (lower plane z_o): kernel = (4 - z_o) / 4 x light size
    // in world, and the frustum at z_o is 2 a (z_o + d) / d wide.
    glm::vec3 P(0.0f, 0.0f, 4.0f);
    float zo = s.planes[1];
    occlusion::SliceLookup l = occlusion::lookupSlice(s, P, 0, occlusion::Fade::Below);
    EXPECT_NEAR(l.uv.x, 0.5f, 1e-6f);
    EXPECT_NEAR(l.uv.y, 0.5f, 1e-6f);
    float worldKernel = (4.0f - zo) / 4.0f * 2.0f, frustum = 2.0f * 1.0f * (zo + s.d) / s.d;
    EXPECT_NEAR(l.kernelTexels.x, worldKernel / frustum * 512.0f, 1e-3f);
    EXPECT_NEAR(l.kernelTexels.y, l.kernelTexels.x / 2.0f, 1e-3f);
    // Fade: slice k counts 0 at its own lower plane, 1 one slice thickness further (below), or
    // ramps inside itself (paper).
    float dz = s.planes[2] - s.planes[1];
    EXPECT_FLOAT_EQ(occlusion::lookupSlice(s, {0, 0, s.planes[1]}, 0, occlusion::Fade::Below).weight, 0.0f);
    EXPECT_NEAR(occlusion::lookupSlice(s, {0, 0, s.planes[1] + 0.5f * dz}, 0, occlusion::Fade::Below).weight, 0.5f, 1e-4f);
    EXPECT_NEAR(occlusion::lookupSlice(s, {0, 0, s.planes[0] + 0.25f * dz}, 0, occlusion::Fade::Paper).weight, 0.25f, 1e-4f);
}

}  // namespace
}  // namespace ss
