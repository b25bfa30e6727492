// Checks dbuffer's volume cache, open and non-manifold occluders, other light shapes and options.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "io/metrics.h"
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

// No NaN or Inf in any layer, V in [0, 1].
// Every layer finite, t and V before any clamping included (debug.raw_layers=true: a NaN or infinity
// from the shaders would otherwise leave the camera pass as 0 or 1).
void expectFinite(const Layers& l, const std::string& what) {
    ASSERT_NE(l.find("raw_t"), nullptr) << what << ": render with debug.raw_layers=true";
    size_t bad = 0;
    for (auto& [name, img] : l.items)
        for (float v : img.pixels) bad += !std::isfinite(v) || (name == "V" && (v < 0.0f || v > 1.0f));
    EXPECT_EQ(bad, 0u) << what;
    EXPECT_EQ(l.items.size(), 12u) << what;  // V, mask, umbra, penumbra, two volumes, four distances, raw t, V
}

Metrics againstReference(Renderer& r, const Scene& scene, const std::string& what,
                         const std::map<std::string, std::string>& options = {}) {
    std::map<std::string, std::string> withRaw = options;
    withRaw["debug.raw_layers"] = "true";
    Layers db = run(r, scene, "dbuffer", 0, withRaw);
    Layers ref = run(r, scene, "reference", referenceSamples());
    expectFinite(db, what);
    Metrics m = compareVisibility(layer(db, "V"), layer(ref, "V"), ref.find("mask"));
    std::printf("[dbuffer] %s: %s\n", what.c_str(), m.toString().c_str());
    return m;
}

TEST(DbufferCache, VolumesAreReusedUntilTheSceneOrLightChanges) {
    Scene scene = test::sceneBox();
    size_t before = dbufferGeometryBuilds();
    auto first = dbufferGeometry(scene, 0, scene.bounds());
    auto again = dbufferGeometry(scene, 0, scene.bounds());
    EXPECT_EQ(dbufferGeometryBuilds(), before + 1);
    EXPECT_EQ(first.get(), again.get());
    // Rendering twice through the renderer re-uses them too.
    Renderer r(SS_BACKEND_AUTO);
    run(r, scene, "dbuffer");
    run(r, scene, "dbuffer");
    EXPECT_EQ(dbufferGeometryBuilds(), before + 1);
    // A moved light is a different scene state: rebuilt, and the volumes move with it.
    test::SceneParams moved;
    moved.lightShift = {0.5f, 0.0f};
    Scene other = test::sceneBox(moved);
    auto shifted = dbufferGeometry(other, 0, other.bounds());
    EXPECT_EQ(dbufferGeometryBuilds(), before + 2);
    EXPECT_NE(shifted->disk.centre, first->disk.centre);
    // An added mesh bumps the revision: rebuilt, with more volume.
    scene.addMesh(test::makeBox({1.0f, 1.0f, 0.5f}, {1.4f, 1.4f, 0.9f}, SS_MESH_CAST));
    auto grown = dbufferGeometry(scene, 0, scene.bounds());
    EXPECT_EQ(dbufferGeometryBuilds(), before + 3);
    EXPECT_GT(grown->volumes.umbra.size() + grown->volumes.penumbra.size(),
              first->volumes.umbra.size() + first->volumes.penumbra.size());
}

// A move rebuilds the moved mesh's volumes only; the others are taken from the last build, and
// the volumes are a fresh scene's, vertex for vertex.
TEST(DbufferCache, AMoveBuildsOnlyTheMovedMeshsVolumes) {
    auto scene = [](float shift) {
        Scene s;
        s.addMesh(test::makeGround(4.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
        s.addMesh(test::makeBox({-0.5f, -0.5f, 0.6f}, {0.5f, 0.5f, 1.0f}, SS_MESH_CAST));
        s.addMesh(test::makeBox({0.8f, 0.6f, 0.3f}, {1.1f, 0.9f, 0.5f}, SS_MESH_CAST));
        s.addLight(test::makeDiskLight({0.5f, 0.3f, 4.0f}, 1.0f));
        s.setCamera(test::makeTopCamera(64, 48));
        if (shift != 0.0f) s.setMeshTransform(2, glm::translate(glm::mat4(1.0f), glm::vec3(shift, 0.0f, 0.0f)));
        return s;
    };
    Scene moving = scene(0.0f);
    auto first = dbufferGeometry(moving, 0, moving.bounds());
    EXPECT_EQ(first->meshesBuilt, 3u);
    moving.setMeshTransform(2, glm::translate(glm::mat4(1.0f), glm::vec3(-0.2f, 0.0f, 0.0f)));
    auto moved = dbufferGeometry(moving, 0, moving.bounds());
    EXPECT_EQ(moved->meshesBuilt, 1u);
    EXPECT_EQ(moved->meshesReused, 2u);
    Scene freshScene = scene(-0.2f);
    auto fresh = dbufferGeometry(freshScene, 0, freshScene.bounds());
    EXPECT_EQ(fresh->meshesReused, 0u);
    auto same = [](const std::vector<VolumeVertex>& a, const std::vector<VolumeVertex>& b) {
        return a.size() == b.size() &&
               std::memcmp(a.data(), b.data(), a.size() * sizeof(VolumeVertex)) == 0;
    };
    EXPECT_TRUE(same(moved->volumes.umbra, fresh->volumes.umbra));
    EXPECT_TRUE(same(moved->volumes.penumbra, fresh->volumes.penumbra));
    EXPECT_FALSE(same(moved->volumes.umbra, first->volumes.umbra));  // the small box's moved
}

Scene withOccluder(Mesh occluder) {
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(std::move(occluder));
    s.addLight(test::makeDiskLight({0.0f, 0.0f, 4.0f}, 1.5f));
    s.setCamera(test::makeTopCamera());
    return s;
}

// Measured RMSE: open plate 0.016, box with fin 0.017 (umbra IoU 0.94; it was 0.032 / 0.56 while
// the first-exit rule discarded umbra exits within 1.5 texels of the caster, which behind a thin
// fin is every exit). Bounds allow reference noise and raster shifts.
TEST(DbufferMeshes, OpenAndNonManifoldOccludersStaySane) {
    Renderer r(SS_BACKEND_AUTO);
    // An open square plate (4 open edges): every border edge is both silhouettes.
    Mesh plate = test::makeGround(0.6f, 1.2f, SS_MESH_CAST);
    EXPECT_EQ(plate.report.openEdges, 4u);
    Metrics mp = againstReference(r, withOccluder(plate), "open plate");
    EXPECT_LT(mp.rmse, 0.04) << mp.toString();
    EXPECT_GT(mp.litIoU, 0.97) << mp.toString();
    // A box with a fin on its top edge: that edge has three faces.
    Mesh box = test::makeBox({-0.6f, -0.6f, 0.8f}, {0.6f, 0.6f, 1.2f}, SS_MESH_CAST);
    uint32_t base = uint32_t(box.objectPositions.size());
    box.objectPositions.push_back({0.0f, 0.6f, 1.8f});
    // The top face's +y edge runs between the vertices with y = 0.6 and z = 1.2.
    uint32_t a = 0, b = 0;
    bool found = false;
    for (uint32_t i = 0; i < base; ++i)
        if (box.objectPositions[i].y == 0.6f && box.objectPositions[i].z == 1.2f) (found ? b : a) = i, found = true;
    box.triangles.push_back({a, b, base});
    box.finalize();
    EXPECT_EQ(box.report.nonManifoldEdges, 1u);
    Metrics mf = againstReference(r, withOccluder(box), "box with fin");
    EXPECT_LT(mf.rmse, 0.05) << mf.toString();
    EXPECT_GT(mf.litIoU, 0.97) << mf.toString();
}

// Occluders usually receive too: their own faces must not come out as garbage.
TEST(DbufferMeshes, ReceivingOccludersStayClose) {
    Renderer r(SS_BACKEND_AUTO);
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(test::makeBox({-0.6f, -0.6f, 0.4f}, {0.6f, 0.6f, 1.2f}, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(test::makeTorus({1.6f, 0.8f, 0.6f}, 0.5f, 0.2f, 32, 16, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addLight(test::makeDiskLight({0.3f, 0.2f, 4.0f}, 1.5f));
    s.setCamera(test::makeTopCamera());
    Metrics m = againstReference(r, s, "receiving occluders");
    EXPECT_LT(m.rmse, 0.06) << m.toString();
    EXPECT_GT(m.litIoU, 0.95) << m.toString();
}

Light shaped(LightType type) {
    Light l = test::makeDiskLight({0.0f, 0.0f, 4.0f}, 1.5f);
    l.type = type;
    if (type == LightType::Square || type == LightType::Rectangle) {
        l.size = 1.33f;  // area-equal to the 1.5 disk
        l.sizeY = type == LightType::Rectangle ? 0.9f : 1.33f;
    }
    if (type == LightType::Point || type == LightType::Spot) {
        l.radius = 0.5f;
        l.spotSize = 2.5f;
    }
    if (type == LightType::Sun) l.angle = 0.2f;
    return l;
}

// Measured RMSE: square 0.017, rectangle 0.018, point 0.010, spot 0.010, sun 0.003 (256
// reference samples); a 0.04 bound leaves room for 64-sample noise and raster shifts.
TEST(DbufferLights, OtherShapesThroughTheirDiskAreClose) {
    Renderer r(SS_BACKEND_AUTO);
    for (LightType type : {LightType::Square, LightType::Rectangle, LightType::Point, LightType::Spot, LightType::Sun}) {
        Scene s;
        s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
        s.addMesh(test::makeBox({-0.6f, -0.6f, 0.8f}, {0.6f, 0.6f, 1.2f}, SS_MESH_CAST));
        s.addLight(shaped(type));
        s.setCamera(test::makeTopCamera());
        Metrics m = againstReference(r, s, lightTypeName(type));
        EXPECT_LT(m.rmse, 0.04) << lightTypeName(type) << ": " << m.toString();
        EXPECT_GT(m.litIoU, 0.97) << lightTypeName(type) << ": " << m.toString();
    }
}

TEST(DbufferOptions, SmallOccluderProfileAndPaperUmbraRule) {
    Renderer r(SS_BACKEND_AUTO);
    Scene scene = test::sceneTorus();
    Layers base = run(r, scene, "dbuffer");
    Layers root = run(r, scene, "dbuffer", 0, {{"small_occluders", "true"}, {"debug.raw_layers", "true"}});
    Layers paper = run(r, scene, "dbuffer", 0, {{"umbra_rule", "farthest"}, {"debug.raw_layers", "true"}});
    expectFinite(root, "small_occluders");
    expectFinite(paper, "umbra_rule=farthest");
    // Same umbra and lit regions (t = 0 and t = 1 map to 0 and 1 either way); in the outer
    // half of the penumbra sqrt(t) is the brighter profile (sqrt(t) > 3t^2 - 2t^3 for t < 0.5).
    size_t brighter = 0, moved = 0;
    for (size_t i = 0; i < layer(base, "V").pixels.size(); ++i) {
        float v0 = layer(base, "V").pixels[i], v1 = layer(root, "V").pixels[i];
        moved += (v0 == 0.0f) != (v1 == 0.0f) || (v0 == 1.0f) != (v1 == 1.0f);
        brighter += v0 < 0.5f && v1 > v0 + 0.01f;
    }
    EXPECT_EQ(moved, 0u);
    EXPECT_GT(brighter, 50u);
    // A misspelt option names itself instead of silently falling back.
    EXPECT_THROW(run(r, scene, "dbuffer", 0, {{"umbra_rule", "nearest"}}), Error);
    EXPECT_THROW(run(r, scene, "dbuffer", 0, {{"profile", "linear"}}), Error);
}

}  // namespace
}  // namespace ss
