// Do see-through materials (alpha cut-outs, 50 % cards) shadow as Cycles' shadow rays say
// (transmission 1 - alpha, multiplied along the ray): exactly in the reference, refine and
// auto, and each GL method as docs/methods/<method>.md says?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "capi/capi_internal.h"
#include "core/error.h"
#include "io/metrics.h"
#include "io/scene_file.h"
#include "reference/light_sampler.h"
#include "reference/sample_sequence.h"
#include "reference/trace_scene.h"
#include "reference/visibility_estimator.h"
#include "renderer/renderer.h"
#include "test_scenes.h"

namespace ss {
namespace {

constexpr float kCardZ = 1.0f, kCardHalf = 1.0f;
constexpr int kChecker = 4;  // texels per side of the checkerboard

// A horizontal square card at kCardZ cut into n x n cells (two triangles each, long thin ones
// when `slanted`), UVs (0, 0) .. (1, 1) over it.
Mesh card(int n, const std::string& name = "card", bool slanted = false) {
    Mesh m;
    m.name = name;
    m.flags = SS_MESH_CAST;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.objectPositions.push_back({-kCardHalf + 2.0f * kCardHalf * float(i) / float(n),
                                         -kCardHalf + 2.0f * kCardHalf * float(j) / float(n), kCardZ});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            if (slanted && (i + j) % 2) m.triangles.push_back({a, b, c}), m.triangles.push_back({b, d, c});
            else m.triangles.push_back({a, b, d}), m.triangles.push_back({a, d, c});
        }
    return m;
}

// Per-corner UVs of a mesh lying in the card's square: the xy position mapped to [0, 1]^2.
std::vector<glm::vec2> cardUvs(const Mesh& m) {
    std::vector<glm::vec2> uvs;
    for (const glm::uvec3& t : m.triangles)
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = m.objectPositions[t[k]];
            uvs.push_back((glm::vec2(p.x, p.y) + kCardHalf) / (2.0f * kCardHalf));
        }
    return uvs;
}

MeshAlpha constantAlpha(const Mesh& m, float alpha) {
    MeshAlpha a;
    a.materials.resize(1);
    a.materials[0].constant = alpha;
    (void)m;
    return a;
}

// A kChecker x kChecker checkerboard, opaque where (i + j) is even, nearest texel.
MeshAlpha checkerAlpha(const Mesh& m) {
    MeshAlpha a;
    a.cornerUvs = cardUvs(m);
    AlphaMaterial mat;
    mat.width = mat.height = kChecker;
    mat.filter = AlphaFilter::Closest;
    mat.wrap = AlphaWrap::Extend;
    for (int j = 0; j < kChecker; ++j)
        for (int i = 0; i < kChecker; ++i) mat.texels.push_back((i + j) % 2 == 0 ? 1.0f : 0.0f);
    a.materials.push_back(mat);
    return a;
}

// The checkerboard's opaque squares as geometry: what the cut-out card must shadow like.
Mesh checkerGeometry() {
    Mesh m;
    m.name = "squares";
    m.flags = SS_MESH_CAST;
    const float cell = 2.0f * kCardHalf / float(kChecker);
    for (int j = 0; j < kChecker; ++j)
        for (int i = 0; i < kChecker; ++i) {
            if ((i + j) % 2) continue;
            const float x0 = -kCardHalf + cell * float(i), y0 = -kCardHalf + cell * float(j);
            const uint32_t base = uint32_t(m.objectPositions.size());
            m.objectPositions.push_back({x0, y0, kCardZ});
            m.objectPositions.push_back({x0 + cell, y0, kCardZ});
            m.objectPositions.push_back({x0 + cell, y0 + cell, kCardZ});
            m.objectPositions.push_back({x0, y0 + cell, kCardZ});
            m.triangles.push_back({base, base + 1, base + 2});
            m.triangles.push_back({base, base + 2, base + 3});
        }
    return m;
}

// Ground (receiving) under the card, a small disk light high above, the top camera.
Scene sceneWith(Mesh occluder, const MeshAlpha* alpha = nullptr, float lightDiameter = 0.5f) {
    Scene s;
    s.addMesh(test::makeGround(6.0f, 0.0f, SS_MESH_RECEIVE));
    const int index = s.addMesh(std::move(occluder));
    if (alpha) s.setMeshAlpha(index, *alpha);
    s.addLight(test::makeDiskLight({0.0f, 0.0f, 4.0f}, lightDiameter));
    s.setCamera(makeLookAtCamera({0.0f, -0.5f, 6.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                 glm::radians(35.0f), 128, 96, 0.1f, 50.0f));
    return s;
}

// Pixels both results hold in their masks (the card does not receive: its pixels are outside).
Image bothMasks(const Layers& a, const Layers& b) {
    Image m = *a.find("mask");
    const Image& other = *b.find("mask");
    for (size_t i = 0; i < m.pixels.size(); ++i) m.pixels[i] = m.pixels[i] > 0.5f && other.pixels[i] > 0.5f ? 1.0f : 0.0f;
    return m;
}

double visibilityAt(const Scene& scene, float x, float y, int samples = 1024, uint32_t seed = 1) {
    TraceScene trace(scene);
    LightSampler light(scene.lights()[0]);
    SurfaceHit hit = trace.intersect(Ray{{x, y, 0.5f}, {0.0f, 0.0f, -1.0f}}, 0.0f, 10.0f);
    EXPECT_TRUE(hit.hit);
    return estimateVisibility(trace, light, hit, SampleSequence(seed, 0, 0), samples).visibility;
}

// Where every shadow ray of a ground point crosses the card (light radius 0.25 at height 4,
// card half-width 1 at height 1: |x|, |y| <= 0.75 - 0.25 * 3 / 4 keeps them all inside).
constexpr float kFullyCovered = 0.5f;

TEST(SeeThroughReference, HalfTransparentCardLetsHalfThrough) {
    for (bool slanted : {false, true}) {
        Mesh c = card(16, "card", slanted);  // many triangles: spatial splits must not count one twice
        MeshAlpha half = constantAlpha(c, 0.5f);
        Scene scene = sceneWith(c, &half);
        for (float x : {0.0f, 0.3f, -kFullyCovered})
            for (float y : {0.0f, 0.17f, kFullyCovered})
                EXPECT_NEAR(visibilityAt(scene, x, y), 0.5, 1e-6) << "at (" << x << ", " << y << ")";
    }
}

TEST(SeeThroughReference, TransmissionsMultiplyAlongTheRay) {
    Scene scene = sceneWith(card(4), nullptr);
    Mesh second = card(3, "second");
    for (glm::vec3& p : second.objectPositions) p.z = 1.5f;
    const int upper = scene.addMesh(second);
    scene.setMeshAlpha(1, constantAlpha(scene.meshes()[1], 0.5f));
    scene.setMeshAlpha(upper, constantAlpha(scene.meshes()[upper], 0.75f));
    // 0.5 x 0.25 under both; a fully transparent third card changes nothing.
    EXPECT_NEAR(visibilityAt(scene, 0.0f, 0.0f), 0.5 * 0.25, 1e-6);
    Mesh third = card(2, "third");
    for (glm::vec3& p : third.objectPositions) p.z = 2.0f;
    const int clear = scene.addMesh(third);
    scene.setMeshAlpha(clear, constantAlpha(scene.meshes()[clear], 0.0f));
    EXPECT_NEAR(visibilityAt(scene, 0.0f, 0.0f), 0.5 * 0.25, 1e-6);
    // Opaque again: the card blocks every ray.
    scene.setMeshAlpha(1, constantAlpha(scene.meshes()[1], 1.0f));
    EXPECT_FALSE(scene.meshes()[1].seeThrough());
    EXPECT_EQ(visibilityAt(scene, 0.0f, 0.0f), 0.0);
}

TEST(SeeThroughReference, CheckerboardCutOutShadowsLikeItsOpaqueSquares) {
    Mesh c = card(2);
    MeshAlpha checker = checkerAlpha(c);
    Scene cut = sceneWith(c, &checker);
    Scene squares = sceneWith(checkerGeometry());
    // The same sample sequence: each ray crosses the card where the squares are or are not.
    for (float x : {-0.6f, -0.25f, 0.0f, 0.1f, 0.4f, 0.7f, 1.2f})
        for (float y : {-0.5f, 0.0f, 0.33f, 0.8f}) {
            const double a = visibilityAt(cut, x, y, 512), b = visibilityAt(squares, x, y, 512);
            EXPECT_NEAR(a, b, 2e-3) << "at (" << x << ", " << y << ")";
        }
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    settings.samples = 256;
    Layers a = renderer.render(cut, 0, "reference", settings, nullptr);
    Layers b = renderer.render(squares, 0, "reference", settings, nullptr);
    const Image mask = bothMasks(a, b);
    const Metrics m = compareVisibility(*a.find("V"), *b.find("V"), &mask);
    EXPECT_LT(m.rmse, 0.003) << m.toString();
    EXPECT_GT(m.pixels, 5000u);
}

TEST(SeeThroughReference, TextureFollowsWrapAndFilter) {
    AlphaMaterial m;
    m.width = 2, m.height = 1;
    m.texels = {0.0f, 1.0f};
    m.wrap = AlphaWrap::Repeat;
    EXPECT_NEAR(m.alphaAt({0.5f, 0.5f}), 0.5f, 1e-6f);   // between the texel centres
    EXPECT_NEAR(m.alphaAt({0.25f, 0.5f}), 0.0f, 1e-6f);  // a texel centre
    EXPECT_NEAR(m.alphaAt({1.25f, 7.5f}), 0.0f, 1e-6f);  // repeated
    EXPECT_NEAR(m.alphaAt({0.0f, 0.5f}), 0.5f, 1e-6f);   // repeat blends the far border
    m.wrap = AlphaWrap::Extend;
    EXPECT_NEAR(m.alphaAt({0.0f, 0.5f}), 0.0f, 1e-6f);
    EXPECT_NEAR(m.alphaAt({3.0f, 0.5f}), 1.0f, 1e-6f);
    m.wrap = AlphaWrap::Clip;
    EXPECT_NEAR(m.alphaAt({3.0f, 0.5f}), 0.0f, 1e-6f);
    m.filter = AlphaFilter::Closest;
    m.wrap = AlphaWrap::Extend;
    EXPECT_EQ(m.alphaAt({0.49f, 0.5f}), 0.0f);
    EXPECT_EQ(m.alphaAt({0.51f, 0.5f}), 1.0f);
}

TEST(SeeThroughScene, BadMaterialsAreRefusedNamingTheMesh) {
    Scene scene = sceneWith(card(1));
    MeshAlpha a = checkerAlpha(scene.meshes()[1]);
    a.cornerUvs.pop_back();
    try {
        scene.setMeshAlpha(1, a);
        FAIL() << "accepted 5 UVs for 2 triangles";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_SCENE);
        EXPECT_NE(std::string(e.what()).find("mesh 'card'"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(scene.meshes()[1].seeThrough());  // left as it was
    MeshAlpha b = constantAlpha(scene.meshes()[1], 1.5f);
    EXPECT_EQ(test::statusOf([&] { scene.setMeshAlpha(1, b); }), SS_ERROR_INVALID_SCENE);
    MeshAlpha c = constantAlpha(scene.meshes()[1], 0.5f);
    c.triangleMaterial = {0, 1};
    EXPECT_EQ(test::statusOf([&] { scene.setMeshAlpha(1, c); }), SS_ERROR_INVALID_SCENE);
}

TEST(SeeThroughScene, SceneFileKeepsTheMaterials) {
    Mesh c = card(2);
    MeshAlpha checker = checkerAlpha(c);
    checker.materials.push_back(AlphaMaterial{});
    checker.materials.back().constant = 0.25f;
    checker.triangleMaterial.assign(c.triangles.size(), 0u);
    checker.triangleMaterial[1] = 1;
    Scene scene = sceneWith(c, &checker);
    const std::string path = ::testing::TempDir() + "see_through_scene.json";
    saveSceneFile(scene, path);
    Scene back = loadSceneFile(path);
    ASSERT_TRUE(back.meshes()[1].seeThrough());
    const MeshAlpha& a = *back.meshes()[1].alpha;
    EXPECT_EQ(a.cornerUvs, checker.cornerUvs);
    EXPECT_EQ(a.triangleMaterial, checker.triangleMaterial);
    ASSERT_EQ(a.materials.size(), 2u);
    EXPECT_EQ(a.materials[0].texels, checker.materials[0].texels);
    EXPECT_EQ(a.materials[0].filter, AlphaFilter::Closest);
    EXPECT_EQ(a.materials[0].wrap, AlphaWrap::Extend);
    EXPECT_EQ(a.materials[1].constant, 0.25f);
    EXPECT_FALSE(back.meshes()[0].seeThrough());
}

TEST(SeeThroughCApi, SetMeshMaterialsCopiesChecksAndClears) {
    ss_scene* scene = nullptr;
    ASSERT_EQ(ss_scene_create(&scene), SS_OK);
    const float xyz[] = {0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    const uint32_t tris[] = {0, 1, 2, 0, 2, 3};
    int32_t index = -1;
    ASSERT_EQ(ss_scene_add_mesh(scene, "card", xyz, 4, tris, 2, nullptr, SS_MESH_CAST, &index), SS_OK);
    const float uvs[] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    float texels[] = {1, 0, 0, 1};
    const int32_t material[] = {0, 1};
    ss_alpha_material m[2] = {};
    m[0].texture = texels, m[0].width = 2, m[0].height = 2, m[0].wrap = SS_ALPHA_WRAP_EXTEND, m[0].closest = 1;
    m[1].alpha = 0.5f;
    ASSERT_EQ(ss_scene_set_mesh_materials(scene, index, uvs, material, m, 2), SS_OK) << ss_last_error();
    texels[0] = 0.0f;  // copied: the scene keeps its own
    const Mesh& mesh = scene->scene.meshes()[0];
    ASSERT_TRUE(mesh.seeThrough());
    EXPECT_EQ(mesh.alpha->materials[0].texels[0], 1.0f);
    EXPECT_EQ(mesh.alpha->materials[1].constant, 0.5f);
    EXPECT_EQ(mesh.alpha->triangleMaterial, (std::vector<uint32_t>{0, 1}));
    const int32_t bad[] = {0, 2};
    EXPECT_EQ(ss_scene_set_mesh_materials(scene, index, uvs, bad, m, 2), SS_ERROR_INVALID_SCENE);
    EXPECT_NE(std::string(ss_last_error()).find("'card'"), std::string::npos) << ss_last_error();
    m[1].alpha = -0.5f;
    EXPECT_EQ(ss_scene_set_mesh_materials(scene, index, uvs, material, m, 2), SS_ERROR_INVALID_SCENE);
    EXPECT_TRUE(scene->scene.meshes()[0].seeThrough());  // a refused set leaves it as it was
    EXPECT_EQ(ss_scene_set_mesh_materials(scene, 7, uvs, material, m, 2), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_scene_set_mesh_materials(scene, index, nullptr, nullptr, nullptr, 0), SS_OK);
    EXPECT_FALSE(scene->scene.meshes()[0].seeThrough());
    ss_scene_destroy(scene);
}

// The GL methods on the two cards: each method's pass on the cut-out against the same method
// on the opaque squares as geometry, and its mean V where the 50 % card covers the whole light
// (the reference's V is exactly 0.5 there); then refined, against the reference.
struct GlCase {
    std::string method;
    double cutoutRmse;         // most RMSE vs the same method on the squares
    double halfLo, halfHi;     // the mean V under the 50 % card lies in [halfLo, halfHi]
    double opaqueCardRmse;     // most RMSE of the cut-out pass vs the same method on the whole
                               // card (the methods that shadow it as opaque; -1: not asserted)
};
void PrintTo(const GlCase& c, std::ostream* os) { *os << c.method; }

class SeeThroughGl : public ::testing::TestWithParam<GlCase> {};

// The ground pixels whose every shadow ray crosses the card (reference V == 0.5 exactly there).
Image fullyCovered(const Layers& reference) {
    const Image& V = *reference.find("V");
    Image m(V.width, V.height, 0.0f);
    for (size_t i = 0; i < m.pixels.size(); ++i) m.pixels[i] = std::abs(V.pixels[i] - 0.5f) < 1e-4f ? 1.0f : 0.0f;
    return m;
}

double meanOver(const Image& v, const Image& mask) {
    double sum = 0.0, n = 0.0;
    for (size_t i = 0; i < v.pixels.size(); ++i)
        if (mask.pixels[i] > 0.5f) sum += v.pixels[i], n += 1.0;
    return n > 0.0 ? sum / n : NAN;
}

TEST_P(SeeThroughGl, HonoursCutOutsAndHalfTransparencyAsDocumented) {
    const GlCase& c = GetParam();
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    settings.samples = 64;
    Mesh cardMesh = card(2);
    MeshAlpha checker = checkerAlpha(cardMesh), half = constantAlpha(cardMesh, 0.5f);
    Scene cut = sceneWith(cardMesh, &checker, 0.3f), squares = sceneWith(checkerGeometry(), nullptr, 0.3f);
    Scene halfCard = sceneWith(cardMesh, &half, 0.3f), opaqueCard = sceneWith(cardMesh, nullptr, 0.3f);

    Layers a = renderer.render(cut, 0, c.method, settings, nullptr);
    Layers b = renderer.render(squares, 0, c.method, settings, nullptr);
    const Image mask = bothMasks(a, b);
    const Metrics cutout = compareVisibility(*a.find("V"), *b.find("V"), &mask);
    Layers o = renderer.render(opaqueCard, 0, c.method, settings, nullptr);
    const Metrics asOpaque = compareVisibility(*a.find("V"), *o.find("V"), o.find("mask"));
    Layers ref = renderer.render(halfCard, 0, "reference", settings, nullptr);
    const Image covered = fullyCovered(ref);
    ASSERT_GT(meanOver(covered, covered), 0.0);
    Layers h = renderer.render(halfCard, 0, c.method, settings, nullptr);
    const double halfMean = meanOver(*h.find("V"), covered);
    std::cout << "  " << c.method << ": cut-out vs squares " << cutout.toString() << "\n  cut-out vs whole card "
              << asOpaque.toString() << "\n  mean V under the 50 % card " << halfMean << "\n";
    EXPECT_LT(cutout.rmse, c.cutoutRmse) << cutout.toString();
    EXPECT_GE(halfMean, c.halfLo);
    EXPECT_LE(halfMean, c.halfHi);
    if (c.opaqueCardRmse >= 0.0) EXPECT_LE(asOpaque.rmse, c.opaqueCardRmse) << asOpaque.toString();

    // Refinement (what final renders use) re-traces what the pass got wrong.
    RenderSettings refine = settings;
    refine.refine = true;
    Layers fixed = renderer.render(halfCard, 0, c.method, refine, nullptr);
    const Metrics refinedHalf = compareVisibility(*fixed.find("V"), *ref.find("V"), ref.find("mask"));
    Layers fixedCut = renderer.render(cut, 0, c.method, refine, nullptr);
    Layers refCut = renderer.render(cut, 0, "reference", settings, nullptr);
    const Metrics refinedCut = compareVisibility(*fixedCut.find("V"), *refCut.find("V"), refCut.find("mask"));
    std::cout << "  refined: 50 % card " << refinedHalf.toString() << "\n  refined: cut-out " << refinedCut.toString()
              << "\n";
    EXPECT_NEAR(meanOver(*fixed.find("V"), covered), 0.5, 0.01) << "refined";
    EXPECT_LT(refinedHalf.rmse, 0.02) << "refined 50 % card: " << refinedHalf.toString();
    EXPECT_LT(refinedCut.rmse, 0.02) << "refined cut-out: " << refinedCut.toString();
}

INSTANTIATE_TEST_SUITE_P(Methods, SeeThroughGl,
                         // Measured: 0 for the four whose light-side pass alpha-tests (the
                         // checkerboard is exactly 0 or 1), 0.039 for dbuffer (its volumes are the
                         // whole card's); 0.515, 0.512, 0.499, 0.515, 0.515 and 0.0002 under the
                         // 50 % card (hashed texels around 0.5; sweep shadows it as opaque).
                         ::testing::Values(GlCase{"shadow_map", 0.005, 0.45, 0.55, -1.0},
                                           GlCase{"pcss", 0.005, 0.45, 0.55, -1.0},
                                           GlCase{"occlusion_textures", 0.005, 0.45, 0.55, -1.0},
                                           GlCase{"penumbra_map", 0.005, 0.45, 0.55, -1.0},
                                           GlCase{"dbuffer", 0.06, 0.45, 0.55, -1.0},
                                           GlCase{"sweep", 1.0, 0.0, 0.02, 1e-6}),
                         [](const auto& info) { return info.param.method; });

TEST(SeeThroughAuto, FinalPassMatchesTheReference) {
    Renderer renderer(SS_BACKEND_AUTO);
    RenderSettings settings;
    Mesh cardMesh = card(2);
    MeshAlpha checker = checkerAlpha(cardMesh), half = constantAlpha(cardMesh, 0.5f);
    for (const MeshAlpha* alpha : {&checker, &half}) {
        Scene scene = sceneWith(cardMesh, alpha, 0.3f);
        RenderSettings refine = settings;
        refine.refine = true;
        Layers autoPass = renderer.render(scene, 0, "auto", refine, nullptr);
        Layers ref = renderer.render(scene, 0, "reference", settings, nullptr);
        const Metrics m = compareVisibility(*autoPass.find("V"), *ref.find("V"), ref.find("mask"));
        std::cout << "  auto + refine (" << (alpha == &half ? "50 % card" : "cut-out") << "): " << m.toString() << "\n";
        EXPECT_LT(m.rmse, 0.015) << (alpha == &half ? "50 % card: " : "cut-out: ") << m.toString();
    }
}

}  // namespace
}  // namespace ss
