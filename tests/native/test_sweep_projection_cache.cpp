// Does sweep project again only the meshes an edit moved or changed, keep the others' projections
// within its budget, and still give a fresh scene's shadow bit for bit?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "methods/sweep/shadow.h"
#include "methods/sweep/weights.h"
#include "planar/outline.h"
#include "planar/rings.h"
#include "sampling/light_samples.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

constexpr uint32_t kBoth = SS_MESH_CAST | SS_MESH_RECEIVE;

// A big torus and a small box beside it over the ground (the benchmark's warm scene, smaller).
Scene torusAndBox(const glm::mat4& boxMove, LightType type = LightType::Disk) {
    Scene s;
    s.addMesh(test::makeGround(5.0f, 0.0f, kBoth));
    s.addMesh(test::makeTorus({0.3f, 0.0f, 1.2f}, 1.0f, 0.3f, 64, 32, kBoth));
    s.addMesh(test::makeBox({-2.0f, 0.6f, 0.4f}, {-1.6f, 1.0f, 0.8f}, kBoth));
    s.setMeshTransform(2, boxMove);
    Light light = test::makeDiskLight({-1.0f, -0.5f, 5.0f}, 0.8f, "Key");
    if (type == LightType::Rectangle) {
        light.type = LightType::Rectangle;
        light.size = 1.2f;
        light.sizeY = 0.6f;
    }
    s.addLight(light);
    s.setCamera(test::makeTopCamera(96, 72));
    return s;
}

glm::mat4 shiftX(float x) { return glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, 0.0f)); }

void expectSameShadow(const SweepShadow& a, const SweepShadow& b) {
    ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
    for (size_t i = 0; i < a.mesh.vertices.size(); ++i) {
        EXPECT_EQ(a.mesh.vertices[i].x, b.mesh.vertices[i].x) << i;
        EXPECT_EQ(a.mesh.vertices[i].y, b.mesh.vertices[i].y) << i;
        EXPECT_EQ(a.mesh.vertices[i].intensity, b.mesh.vertices[i].intensity) << i;
    }
    EXPECT_EQ(a.mesh.indices, b.mesh.indices);
    EXPECT_EQ(a.parts.size(), b.parts.size());
    EXPECT_EQ(a.samplesUsed, b.samplesUsed);
    EXPECT_EQ(a.projection.silhouetteEdges, b.projection.silhouetteEdges);
    EXPECT_EQ(a.projection.fallbackTriangles, b.projection.fallbackTriangles);
}

TEST(SweepProjectionCache, AMoveProjectsOnlyTheMovedMeshAndMatchesAFreshScene) {
    for (int clusters : {1, 3}) {
        SCOPED_TRACE("clusters " + std::to_string(clusters));
        const LightType type = clusters == 1 ? LightType::Disk : LightType::Rectangle;
        SweepOptions o;
        o.clusters = clusters;
        Scene scene = torusAndBox(shiftX(0.0f), type);
        SweepProjectionCache cache;
        SweepShadow first = computeSweepShadow(scene, 0, o, &cache);
        EXPECT_EQ(first.projection.meshesProjected, 2 * clusters);
        EXPECT_EQ(first.projection.meshesReused, 0);
        const size_t held = cache.bytes() - cache.weightedBytes() - cache.filledBytes();
        EXPECT_GT(held, 0u);
        EXPECT_GT(cache.weightedBytes(), 0u);

        for (int frame = 1; frame <= 3; ++frame) {
            scene.setMeshTransform(2, shiftX(0.15f * float(frame)));
            SweepShadow warm = computeSweepShadow(scene, 0, o, &cache);
            EXPECT_EQ(warm.projection.meshesProjected, clusters) << "only the box, once per cluster";
            EXPECT_EQ(warm.projection.meshesReused, clusters) << "the torus's projections were made again";
            Scene fresh = torusAndBox(shiftX(0.15f * float(frame)), type);
            SweepShadow cold = computeSweepShadow(fresh, 0, o);
            EXPECT_EQ(cold.projection.meshesReused, 0);
            expectSameShadow(warm, cold);
        }
        // The moved box's earlier projections were dropped, not added to.
        EXPECT_EQ(cache.bytes() - cache.weightedBytes() - cache.filledBytes(), held);
    }
}

TEST(SweepProjectionCache, EditsOfTheLightOrAnotherMeshAndRemovalsKeepItTrue) {
    SweepOptions o;
    Scene scene = torusAndBox(shiftX(0.0f));
    SweepProjectionCache cache;
    computeSweepShadow(scene, 0, o, &cache);

    // The box reshaped (not moved): projected again, the torus reused.
    scene.updateMesh(2, test::makeBox({-2.2f, 0.5f, 0.3f}, {-1.5f, 1.1f, 0.9f}, kBoth));
    SweepShadow reshaped = computeSweepShadow(scene, 0, o, &cache);
    EXPECT_EQ(reshaped.projection.meshesProjected, 1);
    EXPECT_EQ(reshaped.projection.meshesReused, 1);

    // The light's own edit moves every sample: every mesh is projected again.
    Light light = scene.light(0);
    light.size *= 1.3f;
    scene.updateLight(0, light);
    SweepShadow relit = computeSweepShadow(scene, 0, o, &cache);
    EXPECT_EQ(relit.projection.meshesProjected, 2);
    EXPECT_EQ(relit.projection.meshesReused, 0);

    // Another sample count is another sample set.
    o.samples = 9;
    EXPECT_EQ(computeSweepShadow(scene, 0, o, &cache).projection.meshesProjected, 2);

    // The box removed: its projections go, the torus's stay, and the shadow is the torus's alone.
    const size_t withBox = cache.bytes();
    scene.removeMesh(2);
    SweepShadow removed = computeSweepShadow(scene, 0, o, &cache);
    EXPECT_EQ(removed.projection.meshesProjected, 0);
    EXPECT_EQ(removed.projection.meshesReused, 1);
    EXPECT_LT(cache.bytes(), withBox);
    Scene fresh = scene;  // a copy is a new scene with nothing cached
    expectSameShadow(removed, computeSweepShadow(fresh, 0, o));

    // A second light's projections are its own; removing the light drops them.
    scene.addLight(test::makeDiskLight({1.0f, 1.0f, 4.0f}, 0.5f, "Fill"));
    const size_t oneLight = cache.bytes();
    EXPECT_EQ(computeSweepShadow(scene, 1, o, &cache).projection.meshesProjected, 1);
    EXPECT_GT(cache.bytes(), oneLight);
    EXPECT_EQ(computeSweepShadow(scene, 0, o, &cache).projection.meshesReused, 1);
    scene.removeLight(1);
    computeSweepShadow(scene, 0, o, &cache);
    EXPECT_EQ(cache.bytes(), oneLight);
}

TEST(SweepProjectionCache, ABudgetTooSmallProjectsSampleBySampleWithTheSameResult) {
    SweepOptions o;
    Scene scene = torusAndBox(shiftX(0.0f));
    SweepProjectionCache full;
    computeSweepShadow(scene, 0, o, &full);
    ASSERT_GT(full.bytes(), 0u);
    // Room for the box's projections but not the torus's (the torus is projected first, so
    // it outgrows the room part way and is dropped; the box then fits).
    const size_t room = (full.bytes() - full.weightedBytes() - full.filledBytes()) / 4;
    SweepProjectionCache small(room);
    SweepShadow a = computeSweepShadow(scene, 0, o, &small);
    EXPECT_LE(small.bytes(), room);
    EXPECT_GT(small.bytes(), 0u);
    scene.setMeshTransform(2, shiftX(0.2f));
    SweepShadow b = computeSweepShadow(scene, 0, o, &small);
    EXPECT_EQ(b.projection.meshesReused, 0) << "the torus did not fit, the box moved";
    EXPECT_EQ(b.projection.meshesProjected, 2);
    EXPECT_LE(small.bytes(), room);
    expectSameShadow(b, computeSweepShadow(scene, 0, o));
    SweepProjectionCache none(0);
    expectSameShadow(computeSweepShadow(scene, 0, o, &none), b);
    EXPECT_EQ(none.bytes(), 0u);
    (void)a;
}

// Through the renderer: the second and later frames of an animation render what a fresh
// renderer renders on a freshly built scene, whichever raster draws the shadow mesh.
TEST(SweepProjectionCache, AnAnimatedMoveRendersAsAFreshRenderer) {
    Scene scene = torusAndBox(shiftX(0.0f));
    Renderer warm(SS_BACKEND_AUTO);
    for (const char* raster : {"gl", "cpu"}) {
        RenderSettings settings;
        settings.options = {{"raster", raster}};
        warm.render(scene, 0, "sweep", settings, nullptr);
        for (int frame = 1; frame <= 2; ++frame) {
            scene.setMeshTransform(2, shiftX(0.2f * float(frame)));
            Layers a = warm.render(scene, 0, "sweep", settings, nullptr);
            Renderer cold(SS_BACKEND_AUTO);
            Scene fresh = torusAndBox(shiftX(0.2f * float(frame)));
            Layers b = cold.render(fresh, 0, "sweep", settings, nullptr);
            EXPECT_EQ(a.find("V")->pixels, b.find("V")->pixels) << raster << " frame " << frame;
            EXPECT_EQ(a.find("mask")->pixels, b.find("mask")->pixels) << raster << " frame " << frame;
        }
        scene.setMeshTransform(2, shiftX(0.0f));
    }
}

// The irradiance weights of a moved frame: triangles away from where the outlines changed keep
// their weights, the rest are weighed again, and the shadow and the rendered V and mask are a
// fresh scene's bit for bit.
TEST(SweepProjectionCache, AMoveWeighsOnlyTrianglesNearWhatChanged) {
    for (planar::FillMode fill : {planar::FillMode::Smooth, planar::FillMode::Steps, planar::FillMode::Rings}) {
        SCOPED_TRACE(int(fill));
        SweepOptions o;
        o.fill = fill;
        Scene scene = torusAndBox(shiftX(0.0f));
        SweepProjectionCache cache;
        SweepShadow first = computeSweepShadow(scene, 0, o, &cache);
        EXPECT_EQ(first.weighting.trianglesReused, 0u);
        EXPECT_EQ(first.weighting.trianglesWeighed, first.mesh.indices.size() / 3);

        // Unchanged: every triangle reused.
        SweepShadow same = computeSweepShadow(scene, 0, o, &cache);
        EXPECT_EQ(same.weighting.trianglesWeighed, 0u);
        EXPECT_EQ(same.weighting.trianglesReused, same.mesh.indices.size() / 3);
        expectSameShadow(same, first);

        for (int frame = 1; frame <= 3; ++frame) {
            scene.setMeshTransform(2, shiftX(0.15f * float(frame)));
            SweepShadow warm = computeSweepShadow(scene, 0, o, &cache);
            const size_t triangles = warm.mesh.indices.size() / 3;
            EXPECT_EQ(warm.weighting.trianglesWeighed + warm.weighting.trianglesReused, triangles);
            EXPECT_GT(warm.weighting.trianglesWeighed, 0u) << "the box's shadow moved";
            EXPECT_GT(warm.weighting.trianglesReused, triangles / 2) << "the torus's shadow was weighed again";
            Scene fresh = torusAndBox(shiftX(0.15f * float(frame)));
            SweepShadow cold = computeSweepShadow(fresh, 0, o);
            EXPECT_EQ(cold.weighting.trianglesReused, 0u);
            expectSameShadow(warm, cold);
        }
    }
    // A budget of 0 keeps nothing: every triangle weighed.
    Scene scene = torusAndBox(shiftX(0.0f));
    SweepProjectionCache none(0);
    computeSweepShadow(scene, 0, SweepOptions{}, &none);
    SweepShadow again = computeSweepShadow(scene, 0, SweepOptions{}, &none);
    EXPECT_EQ(again.weighting.trianglesReused, 0u);
    EXPECT_EQ(none.bytes(), 0u);
}

// The box's shadow apart from the torus's: a move fills only the box's part again, and the
// shadow is a fresh scene's; once the box's shadow meets the torus's they are one part, filled
// whole.
TEST(SweepProjectionCache, AMoveFillsOnlyThePartOfTheShadowItReached) {
    for (planar::FillMode fill : {planar::FillMode::Smooth, planar::FillMode::Steps, planar::FillMode::Rings}) {
        SCOPED_TRACE(int(fill));
        SweepOptions o;
        o.fill = fill;
        Scene scene = torusAndBox(shiftX(0.0f));
        SweepProjectionCache cache;
        SweepShadow first = computeSweepShadow(scene, 0, o, &cache);
        EXPECT_EQ(first.filling.partsFilled, 2u);
        EXPECT_EQ(first.filling.partsReused, 0u);
        EXPECT_GT(cache.filledBytes(), 0u);
        for (int frame = 1; frame <= 2; ++frame) {
            scene.setMeshTransform(2, shiftX(0.15f * float(frame)));
            SweepShadow warm = computeSweepShadow(scene, 0, o, &cache);
            EXPECT_EQ(warm.filling.partsFilled, 1u) << "the box's part";
            EXPECT_EQ(warm.filling.partsReused, 1u) << "the torus's part was filled again";
            Scene fresh = torusAndBox(shiftX(0.15f * float(frame)));
            expectSameShadow(warm, computeSweepShadow(fresh, 0, o));
        }
        scene.setMeshTransform(2, shiftX(1.2f));
        SweepShadow met = computeSweepShadow(scene, 0, o, &cache);
        EXPECT_EQ(met.filling.partsFilled, 1u) << "the box's shadow on the torus's: one part";
        EXPECT_EQ(met.filling.partsReused, 0u);
        EXPECT_EQ(cache.filledBytes(), 0u) << "one part is not kept";
        expectSameShadow(met, computeSweepShadow(torusAndBox(shiftX(1.2f)), 0, o));
    }
}

// The guard of the reuse: two samples' outlines swapped leave the merged outlines, and so the
// fill's triangles, as they were, but not which samples shadow each triangle. The triangles inside
// the swapped outlines are weighed again, and the result is a fresh weighing's.
TEST(SweepProjectionCache, KeptWeightsFollowTheSamplesNotTheTriangles) {
    Scene scene = torusAndBox(shiftX(0.0f));
    const Light& light = scene.light(0);
    ReceiverPlane plane = findReceiverPlane(scene, light, "");
    planar::Snap snap(plane.cu, plane.cv, plane.half);
    LightSampleOptions so;
    so.count = 16;
    so.borderShare = 0.25;
    so.viewFrom = plane.origin;
    std::vector<LightSample> samples;
    for (const LightSample& s : placeLightSamples(light, so))
        if (castsOntoPlane(plane, s)) samples.push_back(s);
    ASSERT_EQ(samples.size(), 16u);
    std::vector<std::vector<planar::DirectedEdge>> outlines;
    for (const LightSample& s : samples) {
        std::vector<planar::DirectedEdge> edges;
        ProjectionStats stats;
        for (int i : sweepOccluders(scene, 0, plane)) projectMeshSample(scene.meshes()[i], plane, snap, s, &edges, &stats);
        outlines.push_back(planar::hardOutline(edges));
    }
    const planar::ShadowMesh filled =
        planar::fillShadow(planar::mergeOutlines(outlines), int(samples.size()), planar::FillMode::Smooth);
    WeightedTriangles kept;
    planar::ShadowMesh first = filled;
    WeightStats firstStats;
    weighShadowMesh(first, outlines, samples, light, plane, snap, planar::FillMode::Smooth, kept, &firstStats);
    EXPECT_EQ(firstStats.trianglesReused, 0u);

    std::vector<std::vector<planar::DirectedEdge>> swapped = outlines;
    std::swap(swapped[0], swapped[15]);  // a border sample and an inner one
    planar::ShadowMesh warm = filled, cold = filled;
    WeightStats warmStats;
    weighShadowMesh(warm, swapped, samples, light, plane, snap, planar::FillMode::Smooth, kept, &warmStats);
    weighShadowMesh(cold, swapped, samples, light, plane, snap, planar::FillMode::Smooth);
    EXPECT_GT(warmStats.trianglesWeighed, 0u);
    ASSERT_EQ(warm.vertices.size(), cold.vertices.size());
    size_t differ = 0, changed = 0;
    for (size_t i = 0; i < warm.vertices.size(); ++i) {
        differ += warm.vertices[i].intensity != cold.vertices[i].intensity;
        changed += first.vertices[i].intensity != cold.vertices[i].intensity;
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(changed, 0u) << "the swap changed no weight: the check above could not fail";
}

}  // namespace
}  // namespace ss
