// Checks penumbra_map end to end: sane layers, the monotonic penumbra, collapse to the hard
// shadow, its numbers against the reference, and the paper's two limits shown, not hidden.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "softshadow/softshadow.h"
#include "test_pcss_support.h"

namespace ss::test {
namespace {

TEST(PenumbraMap, AgainstTheReferenceOnTheSharedScenes) {
    for (auto& [name, scene] : sharedScenes(softSceneParams())) {
        Layers ref = renderReference(scene);
        Layers pm = renderWith(scene, "penumbra_map");
        Layers paper = renderWith(scene, "penumbra_map", {{"intensity", "paper"}});
        Layers sm = renderWith(scene, "shadow_map");
        Metrics m = compareToReference(pm, ref);
        Metrics p = compareToReference(paper, ref);
        Metrics h = compareToReference(sm, ref);
        SCOPED_TRACE(name + " penumbra_map: " + m.toString() + "\n paper intensity: " + p.toString() +
                     "\n shadow_map: " + h.toString());
        std::printf("%-12s penumbra_map: %s\n%-12s paper:        %s\n%-12s shadow_map:   %s\n", name.c_str(),
                    m.toString().c_str(), name.c_str(), p.toString().c_str(), name.c_str(), h.toString().c_str());
        EXPECT_EQ(checkLayersSane(pm), "");
        EXPECT_EQ(checkLayersSane(paper), "");
        // The outer edge of the soft shadow is right with either intensity: lit IoU well above
        // the hard shadow map's.
        EXPECT_GT(m.litIoU, h.litIoU + 0.01);
        EXPECT_GT(m.litIoU, 0.94);
        EXPECT_GT(p.litIoU, h.litIoU + 0.01);
        // The default intensity (V = 0.5 at the hard edge rising to 1 as the disk is uncovered)
        // is better than the hard shadow map in RMSE.
        EXPECT_LT(m.rmse, h.rmse - 0.01);
        EXPECT_GT(m.umbraIoU, 0.18);
        // The paper's 3I^2 - 2I^3 fades from 0 at the hard edge, where the truth is about 0.5,
        // so its shadow is too dark and its RMSE worse than the hard shadow map's; the bound
        // pins it so a regression still fails. docs/methods/penumbra_map.md explains both.
        EXPECT_LT(p.rmse, 0.26);
        EXPECT_GT(p.rmse, m.rmse);
    }
}

// Just outside the hard shadow of a long straight edge the edge passes near the light's centre:
// about half the light is seen. The default intensity starts its ramp there at 0.5, like the
// reference; the paper's 3I^2 - 2I^3 starts it at 0. (Before camera.frag read the neighbours of
// a texel that holds the occluder, this first column was fully lit: a bright seam.) Measured:
// reference 0.564, penumbra_map 0.570, paper 0.111.
TEST(PenumbraMap, TheRampStartsAtHalfTheLightAtAStraightEdge) {
    Scene scene;
    scene.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    // A plate whose edge runs along y at x = -0.5; the light off to the side puts the edge's hard
    // shadow on the ground at x = 0.5, beyond the plate as the camera sees it.
    scene.addMesh(makeBox({-6.0f, -6.0f, 1.5f}, {-0.5f, 6.0f, 1.6f}, SS_MESH_CAST));
    scene.addLight(makeDiskLight({-2.0f, 0.0f, 4.0f}, 1.5f));
    scene.setCamera(makeTopCamera());
    Layers ref = renderReference(scene);
    Layers pm = renderWith(scene, "penumbra_map");
    Layers paper = renderWith(scene, "penumbra_map", {{"intensity", "paper"}});
    const Image& hard = *pm.find("hard_shadow");
    const Image& mask = *pm.find("mask");
    double sumRef = 0.0, sumPm = 0.0, sumPaper = 0.0;
    size_t n = 0;
    for (int y = 1; y + 1 < hard.height; ++y)
        for (int x = 1; x + 1 < hard.width; ++x) {
            // Lit pixels next to the hard shadow: the edge's first lit row of pixels.
            if (mask.at(x, y) < 0.5f || hard.at(x, y) > 0.5f) continue;
            if (std::max({hard.at(x - 1, y), hard.at(x + 1, y), hard.at(x, y - 1), hard.at(x, y + 1)}) < 0.5f) continue;
            sumRef += ref.find("V")->at(x, y);
            sumPm += pm.find("V")->at(x, y);
            sumPaper += paper.find("V")->at(x, y);
            ++n;
        }
    ASSERT_GT(n, 50u) << "the edge must cross the image";
    const double vRef = sumRef / double(n), vPm = sumPm / double(n), vPaper = sumPaper / double(n);
    std::printf("first lit column: reference %.3f, penumbra_map %.3f, paper %.3f (%zu pixels)\n", vRef, vPm,
                vPaper, n);
    EXPECT_NEAR(vRef, 0.55, 0.1);  // half the disk plus the pixel's offset from the edge
    EXPECT_NEAR(vPm, vRef, 0.08);
    EXPECT_LT(vPaper, 0.15);
}

TEST(PenumbraMap, RefusesAnUnknownIntensityRule) {
    const Scene scene = sharedScenes(softSceneParams()).front().scene;
    expectSettingRefused(scene, "penumbra_map", {{"intensity", "linear"}}, "intensity");
}

TEST(PenumbraMap, LimitOuterPenumbraOnlyTheInnerPenumbraIsBlack) {
    Scene scene = sceneBox(softSceneParams());
    Layers ref = renderReference(scene);
    Layers pm = renderWith(scene, "penumbra_map");
    Layers sm = renderWith(scene, "shadow_map");
    const Image& vr = *ref.find("V");
    const Image& vp = *pm.find("V");
    const Image& vs = *sm.find("V");
    const Image& mask = *ref.find("mask");
    // Inside the light-centre hard shadow the reference still sees part of the light (the
    // inner penumbra); penumbra_map, whose umbra IS that hard shadow, is black there.
    size_t inner = 0, black = 0;
    double missing = 0.0;
    for (size_t i = 0; i < vr.pixels.size(); ++i) {
        if (mask.pixels[i] <= 0.5f || vs.pixels[i] != 0.0f || vr.pixels[i] < 0.2f) continue;
        ++inner;
        black += vp.pixels[i] == 0.0f;
        missing += vr.pixels[i];
    }
    std::printf("inner penumbra: %zu pixels, %zu black in penumbra_map, mean light missed %.3f\n",
                inner, black, inner ? missing / double(inner) : 0.0);
    EXPECT_GT(inner, 100u) << "the box scene has a visible inner penumbra";
    // Allow 2% for pixels where the two methods' depth comparisons differ at the edge.
    EXPECT_GE(double(black), 0.98 * double(inner));
}

TEST(PenumbraMap, LimitTheUmbraNeverShrinks) {
    // A small occluder under a big light: the true umbra ends above the ground (its apex is
    // 0.4 * 2.8 / (3 - 0.4) = 0.43 below the box, the ground 1.0 below), so the reference has
    // no umbra at all; penumbra_map keeps the whole hard shadow as umbra.
    Scene scene;
    scene.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addMesh(makeBox({-0.2f, -0.2f, 1.0f}, {0.2f, 0.2f, 1.2f}, SS_MESH_CAST));
    scene.addLight(makeDiskLight({0.6f, 0.4f, 4.0f}, 3.0f));
    SceneParams sp = softSceneParams();
    sp.cameraZoom = 2.5f;
    scene.setCamera(sceneBox(sp).camera());
    Layers ref = renderReference(scene);
    Layers pm = renderWith(scene, "penumbra_map");
    Layers sm = renderWith(scene, "shadow_map");
    size_t refUmbra = countBelow(ref, 0.05f);
    size_t pmUmbra = countBelow(pm, 0.05f);
    size_t hard = countBelow(sm, 0.5f);
    std::printf("umbra pixels: reference %zu, penumbra_map %zu, hard shadow %zu\n", refUmbra, pmUmbra,
                hard);
    EXPECT_EQ(refUmbra, 0u);
    EXPECT_GT(hard, 30u);
    EXPECT_GE(pmUmbra, hard);  // the umbra is at least the hard shadow: it never shrinks
}

TEST(PenumbraMap, PenumbraWidensWithTheLightRadius) {
    size_t previous = 0;
    for (float diameter : {0.4f, 1.0f, 2.0f}) {
        SceneParams p = softSceneParams();
        p.lightDiameter = diameter;
        Layers pm = renderWith(sceneBox(p), "penumbra_map");
        size_t n = penumbraPixels(pm);
        SCOPED_TRACE("diameter " + std::to_string(diameter) + ": " + std::to_string(n));
        // Outer penumbra width = L_r (Z_P - Z_V) / Z_V: linear in the radius (2.5x, 2x steps);
        // 1.3x leaves room for the pixel grid.
        EXPECT_GT(double(n), 1.3 * double(previous));
        previous = n;
    }
}

TEST(PenumbraMap, PenumbraWidensAsTheOccluderRisesFromTheReceiver) {
    size_t previous = 0;
    for (float lift : {0.0f, 0.3f, 0.6f}) {
        SceneParams p = softSceneParams();
        p.occluderLift = lift;
        Layers pm = renderWith(sceneBox(p), "penumbra_map");
        size_t n = penumbraPixels(pm);
        SCOPED_TRACE("lift " + std::to_string(lift) + ": " + std::to_string(n));
        // Outer width L_r (Z_P - Z_V) / Z_V grows x1.4 per step (see the pcss test); 1.15x
        // leaves room for the pixel grid.
        EXPECT_GT(double(n), 1.15 * double(previous));
        previous = n;
    }
}

TEST(PenumbraMap, CollapsesToTheHardShadowAsTheRadiusGoesToZero) {
    SceneParams p = softSceneParams();
    p.lightDiameter = 1e-4f;
    SceneParams soft = softSceneParams();
    for (int which = 0; which < 3; ++which) {
        auto make = [&](const SceneParams& sp) {
            return which == 0 ? sceneBox(sp) : which == 1 ? sceneConcave(sp) : sceneTorus(sp);
        };
        Scene scene = make(p);
        Layers pm = renderWith(scene, "penumbra_map");
        Layers wide = renderWith(make(soft), "penumbra_map");
        Layers sm = renderWith(scene, "shadow_map");
        size_t differ = countDiffering(pm, sm, 0.5f);
        // Same map, same hard shadow: only edge pixels whose depth comparison differs (the two
        // methods bias differently) may disagree: at most 1% of the mask.
        EXPECT_LE(double(differ), 0.01 * double(maskPixels(pm))) << differ << " pixels differ";
        // Cones of radius ~0 leave at most stray edge texels grey.
        EXPECT_LT(double(penumbraPixels(pm, 0.05f)), 0.05 * double(penumbraPixels(wide, 0.05f)));
    }
}

Light shaped(LightType type) {
    Light l = makeDiskLight({1.2f, 0.8f, 4.0f}, 1.5f, "shaped");
    l.type = type;
    l.sizeY = 0.8f;
    l.radius = 0.6f;
    l.spotSize = glm::radians(120.0f);
    return l;
}

TEST(PenumbraMap, LightShapesUseTheirEquivalentRadius) {
    // Sphere and disk natively; ellipse, square, rectangle through the area-equal radius: the
    // outer penumbra's pixel count follows the radius.
    for (LightType type : {LightType::Disk, LightType::Ellipse, LightType::Square, LightType::Rectangle,
                           LightType::Point, LightType::Spot}) {
        Scene scene = sceneBox(softSceneParams());
        scene.addLight(shaped(type));
        Layers pm = renderWith(scene, "penumbra_map", {}, 0, 1);
        SCOPED_TRACE(lightTypeName(type));
        EXPECT_EQ(checkLayersSane(pm), "");
        EXPECT_GT(penumbraPixels(pm), 50u);
    }
    Scene scene = sceneBox(softSceneParams());
    Light sun = shaped(LightType::Sun);
    sun.angle = 0.1f;
    scene.addLight(sun);
    try {
        renderWith(scene, "penumbra_map", {}, 0, 1);
        FAIL() << "a sun was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_UNSUPPORTED);
        EXPECT_NE(std::string(e.what()).find("sun"), std::string::npos) << e.what();
    }
}

TEST(PenumbraMap, EachLightHasItsOwnMaps) {
    // Light 1 of a two-light scene renders exactly as it does alone: no map is shared or
    // reused across lights.
    SceneParams p = softSceneParams();
    Scene both = sceneOverlapping(p);
    Light second = makeDiskLight({-1.5f, 0.5f, 3.5f}, 0.8f, "second");
    both.addLight(second);
    Layers first = renderWith(both, "penumbra_map", {}, 0, 0);
    Layers fromBoth = renderWith(both, "penumbra_map", {}, 0, 1);
    Scene alone;
    for (const Mesh& m : both.meshes()) alone.addMesh(m);
    alone.addLight(second);
    alone.setCamera(both.camera());
    Layers fromAlone = renderWith(alone, "penumbra_map");
    EXPECT_EQ(countDiffering(fromBoth, fromAlone, 1e-6f), 0u);
    EXPECT_GT(countDiffering(first, fromBoth, 0.5f), 100u) << "the two lights cast different shadows";
}

TEST(PenumbraMap, ExtraLayersAreThere) {
    Layers pm = renderWith(sceneTorus(softSceneParams()), "penumbra_map");
    for (const char* name : {"V", "mask", "umbra", "penumbra", "penumbra_map", "hard_shadow"})
        EXPECT_NE(pm.find(name), nullptr) << name;
    EXPECT_EQ(checkLayersSane(pm), "");
}

}  // namespace
}  // namespace ss::test
