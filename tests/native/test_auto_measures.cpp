// Checks that `auto` picks the candidate with the least error against the reference, and that
// the error estimate every result carries is close to the error measured over the whole image.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>

#include "core/error.h"
#include "io/metrics.h"
#include "io/scene_file.h"
#include "methods/method.h"
#include "methods/sparse_check.h"
#include "reference/render_reference.h"
#include "reference/trace_pixels.h"
#include "renderer/auto_method.h"
#include "renderer/renderer.h"
#include "test_pcss_support.h"
#include "test_scenes.h"

namespace ss {
namespace {

// RMSE of V over every pixel the light reaches (the reference's mask), whatever the method's
// mask: what a composite multiplies by V, and what auto estimates.
double fullRmse(const Layers& method, const Layers& reference) {
    return compareVisibility(*method.find("V"), *reference.find("V"), reference.find("mask")).rmse;
}

struct Case {
    std::string name;
    Scene scene;
};

std::vector<Case> cases() {
    test::SceneParams p;
    p.width = 128, p.height = 96;
    std::vector<Case> out;
    {
        // A long rectangle light: occlusion_textures (the old rule's pick) is not the best here.
        Scene s = test::sceneBox(p);
        Light l = s.light(0);
        l.type = LightType::Rectangle;
        l.size = 2.5f, l.sizeY = 0.6f;
        Scene r;
        for (const Mesh& m : s.meshes()) r.addMesh(m);
        r.addLight(l);
        r.setCamera(s.camera());
        out.push_back({"rectangle", std::move(r)});
    }
    {
        test::SceneParams big = p;
        big.lightDiameter = 3.0f, big.lightHeight = 3.0f;
        out.push_back({"large_disk", test::sceneBox(big)});
    }
    out.push_back({"torus", test::sceneTorus(p)});
    return out;
}

struct Measured {
    std::map<std::string, double> full, estimate;
    std::string best;
};

Measured measureCandidates(Renderer& renderer, const Scene& scene, const Layers& reference) {
    Measured m;
    RenderSettings withEstimate;
    withEstimate.options["estimate_rmse"] = "1";
    for (const std::string& name : autoCandidates(scene, 0)) {
        std::string used;
        double estimate = 0.0;
        Layers layers;
        try {
            layers = renderer.render(scene, 0, name, withEstimate, &used, &estimate);
        } catch (const Error& e) {
            if (e.status() == SS_ERROR_UNSUPPORTED) continue;
            throw;
        }
        m.full[name] = fullRmse(layers, reference);
        m.estimate[name] = estimate;
        if (m.best.empty() || m.full[name] < m.full[m.best]) m.best = name;
    }
    return m;
}

TEST(AutoMeasures, PicksTheBestCandidateByFullImageRmse) {
    for (Case& c : cases()) {
        Renderer renderer(SS_BACKEND_AUTO);
        const Layers reference = renderer.render(c.scene, 0, "reference", RenderSettings{}, nullptr);
        const Measured m = measureCandidates(renderer, c.scene, reference);
        ASSERT_FALSE(m.best.empty()) << c.name;
        std::string used;
        double estimate = 0.0;
        const Layers autoLayers = renderer.render(c.scene, 0, "auto", RenderSettings{}, &used, &estimate);
        const double autoFull = fullRmse(autoLayers, reference);
        std::string table;
        for (auto& [name, full] : m.full)
            table += " " + name + "=" + std::to_string(full) + "(est " + std::to_string(m.estimate.at(name)) + ")";
        std::cout << c.name << ": auto took " << used << " (estimate " << estimate << ", measured " << autoFull
                  << ");" << table << "\n";
        SCOPED_TRACE(c.name + ": auto took " + used + " at " + std::to_string(autoFull) + "; best " + m.best +
                     " at " + std::to_string(m.full.at(m.best)) + ";" + table);
        ASSERT_TRUE(m.full.count(used));
        EXPECT_DOUBLE_EQ(autoFull, m.full.at(used));  // auto hands out the candidate's own image
        // The best, or a candidate the check cannot tell from it (then the cheaper one).
        EXPECT_TRUE(used == m.best || autoFull <= m.full.at(m.best) * 1.05 + 0.001);
        EXPECT_LE(autoFull, 1.25 * m.full.at(m.best));
        EXPECT_DOUBLE_EQ(estimate, m.estimate.at(used));
        // Never worse than the old rule by the light's shape (on the rectangle it took
        // occlusion_textures, several times the error of the sweep).
        EXPECT_LE(autoFull, m.full.at(chooseAutoMethodByShape(c.scene, 0)));
    }
}

TEST(AutoMeasures, EstimatesAreWithinThirtyPercentOfTheMeasuredRmse) {
    for (Case& c : cases()) {
        Renderer renderer(SS_BACKEND_AUTO);
        const Layers reference = renderer.render(c.scene, 0, "reference", RenderSettings{}, nullptr);
        const Measured m = measureCandidates(renderer, c.scene, reference);
        for (auto& [name, full] : m.full) {
            const double estimate = m.estimate.at(name);
            ASSERT_TRUE(std::isfinite(estimate)) << c.name << " " << name;
            EXPECT_LE(std::abs(estimate - full), std::max(0.3 * full, 0.005))
                << c.name << " " << name << ": estimate " << estimate << ", measured " << full;
        }
    }
}

TEST(AutoMeasures, TheSameSeedGivesTheSameChoiceAndEstimate) {
    Case c = std::move(cases().front());
    std::string first, second;
    double a = 0.0, b = 0.0;
    {
        Renderer renderer(SS_BACKEND_AUTO);
        renderer.render(c.scene, 0, "auto", RenderSettings{}, &first, &a);
    }
    {
        Renderer renderer(SS_BACKEND_AUTO);
        renderer.render(c.scene, 0, "auto", RenderSettings{}, &second, &b);
    }
    EXPECT_EQ(first, second);
    EXPECT_EQ(a, b);
    EXPECT_EQ(sparseCheckPixels(128, 96, 4096, 7), sparseCheckPixels(128, 96, 4096, 7));
    EXPECT_NE(sparseCheckPixels(128, 96, 4096, 7), sparseCheckPixels(128, 96, 4096, 8));
}

TEST(AutoMeasures, WithoutTheCheckItFallsBackToTheShapeRuleAndHasNoEstimate) {
    Case c = std::move(cases().front());
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings noCheck;
    noCheck.options["check_pixels"] = "0";
    std::string used;
    double estimate = 0.0;
    renderer.render(c.scene, 0, "auto", noCheck, &used, &estimate);
    EXPECT_EQ(used, chooseAutoMethodByShape(c.scene, 0));
    EXPECT_TRUE(std::isnan(estimate));
    // A method asked for by name carries no estimate unless asked.
    renderer.render(c.scene, 0, "pcss", RenderSettings{}, &used, &estimate);
    EXPECT_TRUE(std::isnan(estimate));
    RenderSettings typo;
    typo.options["check_pixel"] = "10";
    EXPECT_THROW(renderer.render(c.scene, 0, "auto", typo, &used, &estimate), Error);
}

TEST(AutoMeasures, SparseCheckPixelsCoverTheImageOncePerCell) {
    auto pixels = sparseCheckPixels(512, 512, 4096, 1);
    EXPECT_EQ(pixels.size(), 4096u);
    std::set<std::pair<int, int>> unique(pixels.begin(), pixels.end());
    EXPECT_EQ(unique.size(), pixels.size());
    int left = 0;
    for (auto [x, y] : pixels) {
        ASSERT_TRUE(x >= 0 && x < 512 && y >= 0 && y < 512);
        left += x < 256;
    }
    EXPECT_EQ(left, 2048);  // one per cell: exactly half the cells lie in the left half
    EXPECT_EQ(sparseCheckPixels(4, 3, 4096, 1).size(), 12u);  // a small image is checked whole
}

// The box over a curved open ground (z = 0.04 x^2, a bowl like a photo backdrop) that casts,
// as every Blender object does: every face sees the whole light from above.
Scene boxOverCurvedGround(const test::SceneParams& p) {
    Scene box = test::sceneBox(p);
    Scene s;
    const int n = 24;
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = -8.0f + 16.0f * float(i) / float(n), y = -8.0f + 16.0f * float(j) / float(n);
            positions.emplace_back(x, y, 0.04f * x * x);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            triangles.emplace_back(a, b, d);
            triangles.emplace_back(a, d, c);
        }
    Mesh ground = test::makeMesh(positions, triangles);
    ground.name = "curved ground";
    ground.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    s.addMesh(ground);
    for (const Mesh& m : box.meshes())
        if (!m.receives()) s.addMesh(m);
    s.addLight(box.light(0));
    s.setCamera(box.camera());
    return s;
}

TEST(AutoMeasures, GivesDbufferAnOpenCasterThatSeesTheLightFromOneSide) {
    test::SceneParams p;
    p.width = 96, p.height = 72;
    const Scene s = boxOverCurvedGround(p);
    ASSERT_FALSE(s.meshes()[0].report.closedManifold());
    auto candidates = autoCandidates(s, 0);
    EXPECT_EQ(std::count(candidates.begin(), candidates.end(), "dbuffer"), 1);
    // Its border's volumes point away from the light: no leak, no false shadow.
    const Layers reference = test::renderReference(s);
    EXPECT_LT(fullRmse(test::renderWith(s, "dbuffer"), reference), 0.03);
    // The same ground folded over itself (faces seeing the light from both sides) is not.
    Scene folded = s;
    Mesh bent = s.meshes()[0];
    for (glm::vec3& v : bent.objectPositions) v.z = 2.0f * std::sin(1.5f * v.x);
    folded.updateMesh(0, bent);
    candidates = autoCandidates(folded, 0);
    EXPECT_EQ(std::count(candidates.begin(), candidates.end(), "dbuffer"), 0);
}

TEST(AutoMeasures, NeverGivesDbufferAnOpenCaster) {
    test::SceneParams p;
    p.width = 96, p.height = 72;
    Scene s = test::sceneBox(p);
    Scene open;
    for (const Mesh& m : s.meshes()) {
        Mesh copy = m;
        if (!(m.receives())) copy.triangles.pop_back();  // the box loses a face: open edges
        open.addMesh(copy);
    }
    open.addLight(s.light(0));
    open.setCamera(s.camera());
    auto candidates = autoCandidates(open, 0);
    EXPECT_EQ(std::count(candidates.begin(), candidates.end(), "dbuffer"), 0);
    EXPECT_EQ(std::count(candidates.begin(), candidates.end(), "pcss"), 1);
    auto closed = autoCandidates(s, 0);
    EXPECT_EQ(std::count(closed.begin(), closed.end(), "dbuffer"), 1);
    Renderer renderer(SS_BACKEND_AUTO);
    std::string used;
    renderer.render(open, 0, "auto", RenderSettings{}, &used);
    EXPECT_NE(used, "dbuffer");
}

}  // namespace
}  // namespace ss

namespace ss {
namespace {

TEST(SparseCheck, EqualsTheReferenceImageAtItsPixels) {
    test::SceneParams p;
    p.width = 96, p.height = 72;
    Scene scene = test::sceneTorus(p);
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    settings.seed = 5;
    const Layers reference = renderer.render(scene, 0, "reference", settings, nullptr);
    TraceScene trace(scene);
    const auto pixels = sparseCheckPixels(96, 72, 500, 5);
    // At the reference's fixed sample count: the reference image itself at those pixels.
    const auto exact = tracePixels(trace, scene, 0, pixels, kReferenceDefaultSamples, 5);
    for (const PixelVisibility& px : exact) {
        ASSERT_EQ(px.inMask, reference.find("mask")->at(px.x, px.y) > 0.5f) << px.x << "," << px.y;
        if (px.inMask) ASSERT_EQ(px.visibility, reference.find("V")->at(px.x, px.y)) << px.x << "," << px.y;
    }
    // The check traces adaptively: the same mask, the reference's V within its noise, and the
    // same V exactly wherever the first 16 rays did not agree and the pixel took every sample.
    SparseCheck check = runSparseCheck(trace, scene, 0, 500, 0, 5);
    ASSERT_GT(check.maskedPixels(), 300u);
    double sum = 0.0;
    int n = 0, umbraOrLit = 0;
    for (const PixelVisibility& px : check.truth) {
        ASSERT_EQ(px.inMask, reference.find("mask")->at(px.x, px.y) > 0.5f) << px.x << "," << px.y;
        if (!px.inMask) continue;
        const double d = px.visibility - reference.find("V")->at(px.x, px.y);
        EXPECT_LE(std::abs(d), 0.1) << px.x << "," << px.y;
        sum += d * d, ++n;
        umbraOrLit += px.visibility == 0.0f || px.visibility == 1.0f;
    }
    EXPECT_LE(std::sqrt(sum / n), 0.01);
    EXPECT_GT(umbraOrLit, n / 2);  // most checked pixels are decided by the first round
}

// sweep shades its receiver plane only: where the shadow falls on another receiving surface (a
// low platform on the ground) the check bounds its error before it renders, the bound holds, and
// auto leaves sweep out once a rendered candidate is clearly below it.
TEST(AutoMeasures, SweepsBoundCountsTheSurfacesOffItsPlane) {
    test::SceneParams p;
    p.width = 128, p.height = 96;
    Scene scene = test::sceneBox(p);
    Mesh platform = test::makeBox({-1.2f, -1.2f, 0.0f}, {0.4f, 0.4f, 0.5f}, SS_MESH_CAST | SS_MESH_RECEIVE);
    platform.name = "platform";
    scene.addMesh(platform);
    const Camera& cam = scene.camera();
    TraceScene trace(scene);
    const SparseCheck check =
        runSparseCheck(trace, scene, 0, sparseCheckDefaultPixels(cam.width, cam.height), 0, RenderSettings{}.seed);
    const double bound = createMethod("sweep")->errorLowerBound(check, scene, 0);
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings withEstimate;
    withEstimate.options["estimate_rmse"] = "1";
    double estimate = 0.0;
    renderer.render(scene, 0, "sweep", withEstimate, nullptr, &estimate);
    EXPECT_GT(bound, 0.02);
    EXPECT_LE(bound, estimate * 1.02 + 0.001);
    std::string used;
    Renderer::AutoTrials trials;
    Renderer fresh(SS_BACKEND_AUTO);
    fresh.render(scene, 0, "auto", RenderSettings{}, &used, nullptr, &trials);
    EXPECT_NE(used, "sweep");
    EXPECT_EQ(std::count(trials.rendered.begin(), trials.rendered.end(), "sweep"), 0) << used;
    EXPECT_EQ(std::count(trials.skippedByBound.begin(), trials.skippedByBound.end(), "sweep"), 1);
}

// The check's lower bounds hold for the two methods they describe, and auto renders at most
// three candidates at full size on the test scenes (its prior and the bounds leave out the rest).
TEST(AutoMeasures, RendersAtMostThreeCandidatesAndTheBoundsHold) {
    for (Case& c : cases()) {
        Renderer renderer(SS_BACKEND_AUTO);
        const Camera& cam = c.scene.camera();
        TraceScene trace(c.scene);
        const SparseCheck check =
            runSparseCheck(trace, c.scene, 0, sparseCheckDefaultPixels(cam.width, cam.height), 0, RenderSettings{}.seed);
        for (const char* bounded : {"shadow_map", "penumbra_map"}) {
            RenderSettings withEstimate;
            withEstimate.options["estimate_rmse"] = "1";
            double estimate = 0.0;
            renderer.render(c.scene, 0, bounded, withEstimate, nullptr, &estimate);
            const double bound = createMethod(bounded)->errorLowerBound(check, c.scene, 0);
            EXPECT_GT(bound, 0.0) << c.name << " " << bounded;
            EXPECT_LE(bound, estimate * 1.02 + 0.001) << c.name << " " << bounded;
        }
        EXPECT_EQ(createMethod("pcss")->errorLowerBound(check, c.scene, 0), 0.0);
        Renderer fresh(SS_BACKEND_AUTO);
        std::string used;
        Renderer::AutoTrials trials;
        fresh.render(c.scene, 0, "auto", RenderSettings{}, &used, nullptr, &trials);
        EXPECT_LE(trials.rendered.size(), 3u) << c.name;
        EXPECT_NE(std::find(trials.rendered.begin(), trials.rendered.end(), used), trials.rendered.end());
        const size_t considered =
            trials.rendered.size() + trials.skippedByPrior.size() + trials.skippedByBound.size();
        EXPECT_LE(considered, autoCandidates(c.scene, 0).size()) << c.name;
        EXPECT_GE(considered + 1, autoCandidates(c.scene, 0).size()) << c.name;  // sweep may refuse a scene
    }
}

// At 512x512 a method's error is heavy-tailed (thin lines off by 1 at contacts): the check's
// default of one pixel in 16 keeps the estimate close where 4096 pixels could be off by half.
TEST(SparseCheck, EstimatesHoldAt512OnTheDemoScene) {
    Scene scene = loadSceneFile(SS_SOURCE_DIR "/examples/scenes/demo.json");
    Camera cam = scene.camera();
    cam.width = cam.height = test::quickTests() ? 256 : 512;
    scene.setCamera(cam);
    Renderer renderer(SS_BACKEND_AUTO);
    const Layers reference = renderer.render(scene, 0, "reference", RenderSettings{}, nullptr);
    RenderSettings withEstimate;
    withEstimate.options["estimate_rmse"] = "1";
    for (const char* method : {"pcss", "sweep", "dbuffer", "occlusion_textures"}) {
        double estimate = 0.0;
        const Layers layers = renderer.render(scene, 0, method, withEstimate, nullptr, &estimate);
        const double full = fullRmse(layers, reference);
        std::cout << method << ": estimate " << estimate << ", measured " << full << "\n";
        EXPECT_LE(std::abs(estimate - full), std::max(0.3 * full, 0.005)) << method;
        // At 512 the spread over seeds was about 5 %; at the quick runs' 256 the check holds a
        // quarter of the pixels and only the target (above) is asserted.
        if (!test::quickTests())
            EXPECT_LE(std::abs(estimate - full), 0.15 * full) << method << ": the spread over seeds was about 5 %";
    }
    double estimate = 0.0;
    std::string used;
    const Layers autoLayers = renderer.render(scene, 0, "auto", RenderSettings{}, &used, &estimate);
    const double full = fullRmse(autoLayers, reference);
    std::cout << "auto took " << used << ": estimate " << estimate << ", measured " << full << "\n";
    EXPECT_LE(std::abs(estimate - full), std::max(0.3 * full, 0.005));
}

}  // namespace
}  // namespace ss

namespace ss {
namespace {

// Blender's Suzanne is open (its eyes are separate shells and its back has holes): every method
// must take an open, curved caster, and auto must keep dbuffer away from it.
TEST(AutoMeasures, OpenCurvedCasterEveryMethodRendersAndAutoStaysClose) {
    test::SceneParams p;
    p.width = 128, p.height = 96;
    Scene box = test::sceneBox(p);
    Mesh shell = test::makeUvSphere({0.0f, 0.0f, 1.2f}, 0.7f, 12, 24, SS_MESH_CAST | SS_MESH_RECEIVE);
    std::vector<glm::uvec3> kept;  // the lower half's faces go: an open bowl, rim up
    for (const glm::uvec3& t : shell.triangles)
        if (!(shell.objectPositions[t.x].z < 1.2f && shell.objectPositions[t.y].z < 1.2f && shell.objectPositions[t.z].z < 1.2f) &&
            (shell.objectPositions[t.x].z + shell.objectPositions[t.y].z + shell.objectPositions[t.z].z) / 3.0f > 1.25f)
            kept.push_back(t);
    shell.triangles = kept;
    Scene scene;
    scene.addMesh(box.meshes()[0]);  // the ground
    scene.addMesh(shell);
    scene.addLight(box.light(0));
    scene.setCamera(box.camera());
    ASSERT_FALSE(scene.meshes()[1].report.closedManifold());
    Renderer renderer(SS_BACKEND_AUTO);
    const Layers reference = renderer.render(scene, 0, "reference", RenderSettings{}, nullptr);
    double best = 1e9;
    for (const std::string& name : methodNames()) {
        if (name == "reference") continue;
        const Layers layers = renderer.render(scene, 0, name, RenderSettings{}, nullptr);
        for (float v : layers.find("V")->pixels) ASSERT_TRUE(std::isfinite(v)) << name;
        const double rmse = fullRmse(layers, reference);
        std::cout << name << " " << rmse << "\n";
        if (name != "dbuffer") best = std::min(best, rmse);
    }
    std::string used;
    double estimate = 0.0;
    const double autoRmse = fullRmse(renderer.render(scene, 0, "auto", RenderSettings{}, &used, &estimate), reference);
    std::cout << "auto took " << used << " " << autoRmse << " (estimate " << estimate << ")\n";
    EXPECT_NE(used, "dbuffer");
    EXPECT_LE(autoRmse, 1.25 * best);
    EXPECT_LE(std::abs(estimate - autoRmse), std::max(0.3 * autoRmse, 0.005));
}

}  // namespace
}  // namespace ss
