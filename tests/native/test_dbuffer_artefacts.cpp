// Checks that dbuffer's demo image has no self-shadow speckles on the torus and no dark dots in its penumbra.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "io/metrics.h"
#include "io/scene_file.h"
#include "methods/method.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::layer;
using test::run;

// The built-in example (a tilted torus and a cube over the ground under a disk light) at
// width x height (same picture), with only the meshes named in `receivers` receiving: the mask
// of a render then tells which pixels show those meshes.
Scene demo(int width, int height, const std::vector<std::string>& receivers) {
    Scene file = loadSceneFile(SS_SOURCE_DIR "/examples/scenes/demo.json");
    Scene s;
    for (Mesh m : file.meshes()) {
        bool receives = std::find(receivers.begin(), receivers.end(), m.name) != receivers.end();
        m.flags = (m.flags & ~uint32_t(SS_MESH_RECEIVE)) | (receives ? uint32_t(SS_MESH_RECEIVE) : 0u);
        s.addMesh(std::move(m));
    }
    for (const Light& l : file.lights()) s.addLight(l);
    Camera cam = file.camera();
    cam.width = width;
    cam.height = height;
    s.setCamera(cam);
    return s;
}

// Dark specks: masked pixels more than 0.25 darker than every pixel of the ring at distance 2
// around them (16 pixels, all masked). That catches dots up to 3 x 3 pixels wherever they sit —
// the dots this guards against sat in the penumbra at V = 0 among neighbours of ~0.5, where "V <
// 0.3 among neighbours above 0.7" would miss them — while a smooth penumbra (tens of pixels
// wide here) never drops by 0.25 over two pixels.
size_t darkSpecks(const Image& V, const Image& mask) {
    size_t n = 0;
    auto at = [&](const Image& img, int x, int y) { return img.pixels[size_t(y) * img.width + x]; };
    for (int y = 2; y + 2 < V.height; ++y)
        for (int x = 2; x + 2 < V.width; ++x) {
            if (at(mask, x, y) < 0.5f) continue;
            float ringMin = 1e30f;
            bool ringMasked = true;
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    if (std::max(std::abs(dx), std::abs(dy)) != 2) continue;
                    ringMasked = ringMasked && at(mask, x + dx, y + dy) > 0.5f;
                    ringMin = std::min(ringMin, at(V, x + dx, y + dy));
                }
            n += ringMasked && at(V, x, y) < ringMin - 0.25f;
        }
    return n;
}

// Measured on this machine (Release; reference 128 samples at 640 x 480, 64 at 320 x 240), before
// -> after the fix, at 640 x 480 / 320 x 240:
//   lit torus pixels (reference V > 0.95) that dbuffer darkened below 0.8: 297 -> 0 of 14,853 /
//   74 -> 0 of 3,705 (penumbra quads start on the torus's own surface, and the lit branch had no
//   receiver bias: V ~ 0.5 speckles along the penumbra silhouette);
//   dark specks on the ground: 70 -> 0 / 8 -> 0 (a ray grazing the torus leaves the umbra volume
//   a millimetre behind it; the first-exit rule discarded exits within 1.5 texels of the caster,
//   and "no exit" is umbra: V = 0 dots along the centre's hard-shadow boundary);
//   RMSE 0.0260 -> 0.0185 / 0.0263 -> 0.0191. The reference shows no specks (checked below).
TEST(DbufferArtefacts, DemoTorusIsLitOnTopAndItsPenumbraHasNoDarkDots) {
    const bool quick = test::quickTests();
    const int w = quick ? 320 : 640, h = quick ? 240 : 480;
    Renderer r(SS_BACKEND_AUTO);
    Scene all = demo(w, h, {"Ground", "Torus", "Cube"});
    Layers ref = run(r, all, "reference", quick ? 64 : 128);
    Layers db = run(r, all, "dbuffer");
    const Image& V = layer(db, "V");
    const Image& refV = layer(ref, "V");
    // Compared where both masks hold (the rasterised and the ray-traced mask differ on a few
    // dozen pixels at the meshes' outlines).
    Image mask = layer(ref, "mask");
    for (size_t i = 0; i < mask.pixels.size(); ++i) mask.pixels[i] *= layer(db, "mask").pixels[i];

    // Which pixels show the torus, which the ground: the masks of renders where only they receive.
    Image torus = layer(run(r, demo(w, h, {"Torus"}), "dbuffer"), "mask");
    Image ground = layer(run(r, demo(w, h, {"Ground"}), "dbuffer"), "mask");

    size_t litTop = 0, darkened = 0;
    for (size_t i = 0; i < V.pixels.size(); ++i) {
        if (torus.pixels[i] < 0.5f || mask.pixels[i] < 0.5f || refV.pixels[i] <= kLitThreshold) continue;
        ++litTop;
        darkened += V.pixels[i] < 0.8f;
    }
    size_t groundSpecks = darkSpecks(V, ground), torusSpecks = darkSpecks(V, torus);
    size_t refSpecks = darkSpecks(refV, ground) + darkSpecks(refV, torus);
    Metrics m = compareVisibility(V, refV, &mask);
    std::printf("[dbuffer] demo %dx%d: lit torus pixels %zu, darkened below 0.8: %zu; dark specks on the ground %zu, on "
                "the torus %zu (reference %zu); %s\n",
                w, h, litTop, darkened, groundSpecks, torusSpecks, refSpecks, m.toString().c_str());
    ASSERT_GT(litTop, size_t(w * h / 40)) << "the torus is no longer in view";
    // The reference's own noise at 64 samples cannot make a lit pixel (V > 0.95) one dbuffer
    // should darken below 0.8; the few left are the documented limits (faces at the centre's
    // horizon), measured 0. One per thousand leaves room for rasterisation differences.
    EXPECT_LE(darkened, litTop / 1000) << "self-shadow speckles on the lit torus";
    EXPECT_EQ(refSpecks, 0u) << "the speck detector fires on the reference: it no longer means anything";
    EXPECT_LE(groundSpecks, 1u) << "dark dots in the penumbra on the ground";
    EXPECT_LE(torusSpecks, 1u) << "dark dots on the torus";
    EXPECT_LT(m.rmse, 0.022) << m.toString();
}

}  // namespace
}  // namespace ss
