// Checks dbuffer against the ray-traced reference on the shared scenes, and against shadow_map.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "geometry/silhouette.h"
#include "io/metrics.h"
#include "io/png_preview.h"
#include "methods/dbuffer/geometry.h"
#include "methods/method.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::layer;
using test::run;

int referenceSamples() { return test::quickTests() ? 64 : 256; }

// Every layer finite, t and V before clamping included (raw_t, raw_V: a NaN or infinity from the
// shaders shows there); V in [0, 1]; masks exactly 0 or 1; distances >= 0; V = 1 outside the mask.
void expectSaneLayers(const Layers& l, const std::string& what) {
    for (const char* name : {"V", "mask", "umbra", "penumbra", "umbra_volume", "penumbra_volume", "dist_occluder",
                             "dist_umbra", "dist_penumbra", "dist_silhouette", "raw_t", "raw_V"})
        ASSERT_NE(l.find(name), nullptr) << what << ": no layer " << name;
    const Image& V = layer(l, "V");
    const Image& mask = layer(l, "mask");
    size_t bad = 0;
    for (auto& [name, img] : l.items) {
        ASSERT_EQ(img.width, V.width);
        ASSERT_EQ(img.height, V.height);
        for (size_t i = 0; i < img.pixels.size(); ++i) {
            float v = img.pixels[i];
            bool ok = std::isfinite(v);
            if (name == "V") ok = ok && v >= 0.0f && v <= 1.0f && (mask.pixels[i] > 0.5f || v == 1.0f);
            else if (name == "mask" || name == "umbra" || name == "penumbra" || name == "umbra_volume" ||
                     name == "penumbra_volume")
                ok = ok && (v == 0.0f || v == 1.0f);
            else if (name != "raw_t" && name != "raw_V") ok = ok && v >= 0.0f;
            if (!ok) ++bad;
        }
    }
    EXPECT_EQ(bad, 0u) << what << ": pixels out of range or not finite";
}

struct Bounds3 {
    double rmse, umbraIoU, litIoU;
};

// Bounds measured on this machine (Release, 256 reference samples) with margin for reference
// noise (64 samples under SS_TEST_QUICK adds about 0.005 RMSE) and rasterisation differences:
//            measured rmse / umbra IoU / lit IoU        bound
//  box        0.017 / 0.939 / 0.998                      0.025 / 0.85 / 0.99
//  concave    0.018 / 0.823 / 0.997                      0.030 / 0.72 / 0.99
//  overlapping 0.022 / 0.880 / 0.995                     0.045 / 0.50 / 0.98
// Overlapping occluders are the paper's own failure case 1 (one farthest surface per texel); as
// two separate parts each keeps its own exit now (docs/methods/dbuffer.md, "Many parts"), but
// the bound stays the loosest.
TEST(DbufferQuality, SharedScenesMatchReferenceAndBeatShadowMap) {
    Renderer renderer(SS_BACKEND_AUTO);
    const std::map<std::string, Bounds3> bounds = {
        {"box", {0.025, 0.85, 0.99}}, {"concave", {0.030, 0.72, 0.99}}, {"overlapping", {0.045, 0.50, 0.98}}};
    test::SceneParams params;
    // SS_DBUFFER_DUMP=<directory>: also render at 480 x 360 and write every layer as a PNG there.
    const char* dump = getenv("SS_DBUFFER_DUMP");
    if (dump) params.width = 480, params.height = 360;
    for (auto& [name, scene] : test::sharedScenes(params)) {
        Layers ref = run(renderer, scene, "reference", referenceSamples());
        Layers db = run(renderer, scene, "dbuffer", 0, {{"debug.raw_layers", "true"}});
        Layers sm = run(renderer, scene, "shadow_map");
        expectSaneLayers(db, name);
        const Image* mask = ref.find("mask");
        EXPECT_EQ(layer(db, "mask").pixels, mask->pixels) << name << ": the mask differs from the reference's";
        Metrics mdb = compareVisibility(layer(db, "V"), layer(ref, "V"), mask);
        Metrics msm = compareVisibility(layer(sm, "V"), layer(ref, "V"), mask);
        std::printf("[dbuffer] %s dbuffer: %s\n[dbuffer] %s shadow_map: %s\n", name.c_str(),
                    mdb.toString().c_str(), name.c_str(), msm.toString().c_str());
        if (dump) {
            writePngPreview(std::string(dump) + "/" + name + "_ref.png", layer(ref, "V"));
            for (auto& [ln, img] : db.items) {
                Image v = img;
                if (ln.rfind("dist_", 0) == 0) for (float& x : v.pixels) x /= 10.0f;
                writePngPreview(std::string(dump) + "/" + name + "_db_" + ln + ".png", v);
            }
        }
        Layers seg = run(renderer, scene, "dbuffer", 0, {{"profile", "segment"}, {"debug.raw_layers", "true"}});
        expectSaneLayers(seg, name + " segment");
        Metrics mseg = compareVisibility(layer(seg, "V"), layer(ref, "V"), mask);
        std::printf("[dbuffer] %s dbuffer profile=segment: %s\n", name.c_str(), mseg.toString().c_str());
        auto it = bounds.find(name);
        if (it == bounds.end()) continue;  // the torus is recorded, not bounded
        EXPECT_LT(mdb.rmse, it->second.rmse) << name << ": " << mdb.toString();
        EXPECT_GT(mdb.umbraIoU, it->second.umbraIoU) << name << ": " << mdb.toString();
        EXPECT_GT(mdb.litIoU, it->second.litIoU) << name << ": " << mdb.toString();
        EXPECT_LT(mdb.rmse, msm.rmse) << name << ": dbuffer " << mdb.toString() << " vs shadow_map " << msm.toString();
        // The exact segment profile (measured rmse 0.018 / 0.018 / 0.031, umbra IoU 0.94 / 0.99 /
        // 0.81) stays within the same RMSE bounds.
        EXPECT_LT(mseg.rmse, it->second.rmse) << name << " profile=segment: " << mseg.toString();
    }
}

// The paper's Figure 1: a thin plate and a tall box with the same top square have the same
// silhouette from the light centre, but under the disk the box's sides are silhouette faces and
// its umbra silhouette is its bottom square, so its umbra is larger.
// A low camera looks under the boxes at the ground where both umbrae lie.
const glm::vec3 kFigure1Light(0.0f, 0.0f, 4.0f);
Scene figure1Scene(float bottom) {
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(test::makeBox({-0.5f, -0.5f, bottom}, {0.5f, 0.5f, 2.5f}, SS_MESH_CAST));
    s.addLight(test::makeDiskLight(kFigure1Light, 1.5f));
    s.setCamera(makeLookAtCamera({0.0f, -5.0f, 0.4f}, {0.0f, 0.0f, 0.05f}, {0.0f, 0.0f, 1.0f},
                                 glm::radians(40.0f), 160, 120, 0.1f, 50.0f));
    return s;
}

TEST(DbufferQuality, Figure1SameCentreSilhouetteDifferentShadows) {
    Scene plate = figure1Scene(2.45f), tall = figure1Scene(0.5f);
    const Mesh& mp = plate.meshes()[1];
    const Mesh& mt = tall.meshes()[1];
    glm::vec3 c = kFigure1Light;
    // Same point silhouette: the top square (same 4 edges, same coordinates).
    auto topSquare = [&](const Mesh& m) {
        std::vector<std::pair<glm::vec3, glm::vec3>> e;
        for (const SilhouetteEdge& s : pointSilhouette(m, c).edges) e.emplace_back(m.objectPositions[s.a], m.objectPositions[s.b]);
        std::sort(e.begin(), e.end(), [](auto& x, auto& y) { return x.first.x + 3 * x.first.y < y.first.x + 3 * y.first.y; });
        return e;
    };
    EXPECT_EQ(topSquare(mp), topSquare(mt));
    // Different disk silhouettes: the tall box's umbra silhouette is its bottom square.
    Disk d{c, {0, 0, -1}, 0.75f};
    DiskSilhouette sp = diskSilhouette(mp, d), st = diskSilhouette(mt, d);
    EXPECT_FALSE(st.silhouetteFacesCentreBack.empty());
    int bottomEdges = 0;
    for (const SilhouetteEdge& e : st.umbraEdges) bottomEdges += mt.objectPositions[e.a].z == 0.5f && mt.objectPositions[e.b].z == 0.5f;
    EXPECT_GE(bottomEdges, 1);
    for (const SilhouetteEdge& e : sp.umbraEdges) EXPECT_NE(mp.objectPositions[e.a].z, 0.5f);

    Renderer renderer(SS_BACKEND_AUTO);
    Layers dbP = run(renderer, plate, "dbuffer", 0, {{"debug.raw_layers", "true"}});
    Layers dbT = run(renderer, tall, "dbuffer", 0, {{"debug.raw_layers", "true"}});
    Layers refP = run(renderer, plate, "reference", referenceSamples());
    Layers refT = run(renderer, tall, "reference", referenceSamples());
    Layers smP = run(renderer, plate, "shadow_map"), smT = run(renderer, tall, "shadow_map");
    expectSaneLayers(dbP, "plate");
    expectSaneLayers(dbT, "tall");
    // Compare where the ground is seen in both scenes (the tall box hides more of it).
    Image common = layer(refP, "mask");
    for (size_t i = 0; i < common.pixels.size(); ++i) common.pixels[i] *= layer(refT, "mask").pixels[i];
    const Image* mask = &common;
    auto count = [&](const Image& V) {
        size_t n = 0;
        for (size_t i = 0; i < V.pixels.size(); ++i) n += common.pixels[i] > 0.5f && V.pixels[i] < kUmbraThreshold;
        return n;
    };
    size_t uP = count(layer(dbP, "V")), uT = count(layer(dbT, "V"));
    size_t rP = count(layer(refP, "V")), rT = count(layer(refT, "V"));
    std::printf("[dbuffer] figure 1 umbra pixels: plate %zu (reference %zu), tall %zu (reference %zu)\n", uP, rP, uT, rT);
    EXPECT_GT(rT, 2 * rP) << "the scene no longer shows the effect";
    // Measured 96 vs 58 px: eq. 4's smoothstep is darker than the disk's true segment area near
    // t = 0, so the plate's small umbra comes out too big (see docs); still clearly different.
    EXPECT_GT(uT * 10, uP * 14) << "dbuffer gives (nearly) the same umbra to both occluders";
    // shadow_map cannot tell them apart: its two images are identical on the receiver.
    Metrics same = compareVisibility(layer(smP, "V"), layer(smT, "V"), mask);
    EXPECT_GT(same.umbraIoU, 0.99);
    // Each dbuffer image matches its own reference's boundaries (measured: plate umbra/lit IoU
    // 0.59 / 0.988, tall 0.98 / 0.988; the plate's umbra is a thin sliver of ~35 px, so one
    // pixel row moves its IoU by ~0.1: bounds below leave that room).
    Metrics mP = compareVisibility(layer(dbP, "V"), layer(refP, "V"), mask);
    Metrics mT = compareVisibility(layer(dbT, "V"), layer(refT, "V"), mask);
    std::printf("[dbuffer] figure 1 plate: %s\n[dbuffer] figure 1 tall: %s\n", mP.toString().c_str(), mT.toString().c_str());
    EXPECT_GT(mP.umbraIoU, 0.45) << mP.toString();
    EXPECT_GT(mT.umbraIoU, 0.90) << mT.toString();
    EXPECT_GT(mP.litIoU, 0.97) << mP.toString();
    EXPECT_GT(mT.litIoU, 0.97) << mT.toString();
    // The tall box's shadow matches its own reference far better than the plate's reference:
    // its umbra boundary really moved.
    Metrics crossT = compareVisibility(layer(dbT, "V"), layer(refP, "V"), mask);
    EXPECT_LT(crossT.umbraIoU + 0.2, mT.umbraIoU) << crossT.toString();
}

}  // namespace
}  // namespace ss
