// Do the faces of a lit caster that see the light stay lit in every method? A convex occluder
// cannot shadow itself: wherever the light reaches its surface the reference says V = 1, also on
// faces that see part of the light but not its centre (a box's sides under a light wider than
// its top, a sphere's band between the centre's terminator and the light's).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "test_pcss_support.h"
#include "test_scenes.h"

namespace ss {
namespace {

// A box or a sphere, casting and receiving, over a ground plane under a light 3 m across (a disk,
// or a 1.5 x 3 rectangle) 2.6 m above the box's top; the camera sees the top and the side
// turned to it, which faces away from the light's centre but sees the near part of the light.
Scene litCasterScene(bool sphere, bool rectangle, bool groundReceives) {
    const uint32_t both = SS_MESH_CAST | SS_MESH_RECEIVE;
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, groundReceives ? both : SS_MESH_CAST));
    if (sphere) s.addMesh(test::makeUvSphere({0.0f, 0.0f, 1.0f}, 0.6f, 24, 32, both));
    else s.addMesh(test::makeBox({-0.6f, -0.6f, 0.6f}, {0.6f, 0.6f, 1.4f}, both));
    Light light = test::makeDiskLight({0.8f, 0.5f, 4.0f}, 3.0f);
    if (rectangle) {
        light.type = LightType::Rectangle;
        light.name = "Rectangle";
        light.size = 1.5f;  // across x; 3 m along y, towards the side the camera sees
    }
    s.addLight(light);
    const int w = test::quickTests() ? 96 : 160, h = test::quickTests() ? 72 : 120;
    s.setCamera(makeLookAtCamera({0.0f, -3.0f, 4.5f}, {0.0f, 0.0f, 1.0f}, {0, 0, 1}, glm::radians(40.0f), w,
                                 h, 0.1f, 100.0f));
    return s;
}

// Bounds on each method's RMSE over the whole image: its own error on the ground (a hard shadow
// for shadow_map, penumbra_map's outward-only penumbra), below what it was with the caster's faces
// black (shadow_map 0.25, pcss 0.047, dbuffer 0.19, penumbra_map 0.24, occlusion_textures 0.17 on
// the box; sweep shades the ground only: 0.023).
double allSurfacesBound(const std::string& method) {
    if (method == "shadow_map") return 0.18;
    if (method == "penumbra_map") return 0.17;
    if (method == "occlusion_textures") return 0.085;
    if (method == "dbuffer") return 0.08;
    if (method == "pcss") return 0.05;
    return 0.03;
}

// The reference of each scene, rendered once for the six methods.
const Layers& referenceOf(bool sphere, bool rectangle) {
    static std::map<std::pair<bool, bool>, Layers> cache;
    auto it = cache.find({sphere, rectangle});
    if (it == cache.end())
        it = cache
                 .emplace(std::make_pair(sphere, rectangle),
                          test::renderReference(litCasterScene(sphere, rectangle, true)))
                 .first;
    return it->second;
}

using Case = std::tuple<std::string, bool, bool>;  // method, sphere, rectangle

class LitCasterFaces : public ::testing::TestWithParam<Case> {};

TEST_P(LitCasterFaces, StayLitAndTheWholeImageHolds) {
    const auto& [method, sphere, rectangle] = GetParam();
    const Scene scene = litCasterScene(sphere, rectangle, true);
    const Layers& ref = referenceOf(sphere, rectangle);
    // The occluder's pixels that the light reaches: the mask of the same scene with only the
    // occluder receiving (every method's mask is the contract's lightReaches).
    const Layers occluderOnly = test::renderWith(litCasterScene(sphere, rectangle, false), "shadow_map");
    const Layers got = test::renderWith(scene, method);
    const Image &rv = *ref.find("V"), &om = *occluderOnly.find("mask"), &v = *got.find("V");
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < rv.pixels.size(); ++i)
        if (om.pixels[i] > 0.5f)
            sum += double(v.pixels[i] - rv.pixels[i]) * (v.pixels[i] - rv.pixels[i]), ++n;
    ASSERT_GT(n, int(rv.pixels.size()) / 20) << "the occluder must fill part of the view";
    const double occluder = std::sqrt(sum / n), all = test::compareToReference(got, ref).rmse;
    const std::string name = method + (sphere ? "_sphere" : "_box") + (rectangle ? "_rectangle" : "_disk");
    test::dumpPng("lit_caster_" + name, v);
    std::printf("%s: occluder %.4f (%d pixels), all surfaces %.4f\n", name.c_str(), occluder, n, all);
    // Reading their own mesh from the light centre's map (or from the slices above), shadow_map
    // and penumbra_map had 0.56 on the box and 0.21-0.24 on the sphere, dbuffer 0.49-0.52 and
    // 0.15-0.17, occlusion_textures 0.44 and 0.24, pcss 0.050 on the box under the rectangle
    // (docs/gl.md, "Lit caster faces"); pcss and sweep had 0 elsewhere.
    EXPECT_LT(occluder, 0.03) << name;
    EXPECT_LT(all, allSurfacesBound(method)) << name;
}

}  // namespace
}  // namespace ss

namespace ss {
namespace {
INSTANTIATE_TEST_SUITE_P(Methods, LitCasterFaces,
                         ::testing::Combine(::testing::Values("shadow_map", "pcss", "dbuffer", "penumbra_map",
                                                              "occlusion_textures", "sweep"),
                                            ::testing::Bool(), ::testing::Bool()),
                         [](const auto& info) {
                             return std::get<0>(info.param) + (std::get<1>(info.param) ? "_sphere" : "_box") +
                                    (std::get<2>(info.param) ? "_rectangle" : "_disk");
                         });
}  // namespace
}  // namespace ss

namespace ss {
namespace {

// A wall whose face turned to the camera does not see the light's centre (behind the wall) but
// sees its near part, under an overhang that blocks all of that part: the truth is umbra on the
// whole face. The map's ray from the centre reaches the face through the wall, so what shadows it
// is found by the march towards the light it sees (shadow_map, dbuffer, penumbra_map) or pcss's
// kernel, not at its own texel.
Scene overhangScene(bool onlyWallReceives) {
    const uint32_t both = SS_MESH_CAST | SS_MESH_RECEIVE, other = onlyWallReceives ? SS_MESH_CAST : both;
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, other));
    s.addMesh(test::makeBox({-1.0f, -0.2f, 0.0f}, {1.0f, 0.2f, 1.5f}, both));
    s.addMesh(test::makeBox({-1.0f, -1.0f, 1.5f}, {1.0f, 0.2f, 1.7f}, other));
    s.addLight(test::makeDiskLight({0.0f, 0.6f, 4.0f}, 3.0f));
    const int w = test::quickTests() ? 96 : 160, h = test::quickTests() ? 72 : 120;
    s.setCamera(makeLookAtCamera({0.0f, -5.0f, 1.2f}, {0.0f, 0.0f, 0.8f}, {0, 0, 1}, glm::radians(40.0f), w,
                                 h, 0.1f, 100.0f));
    return s;
}

class UnseenCentre : public ::testing::TestWithParam<std::string> {};

TEST_P(UnseenCentre, AnOverhangShadowsTheFaceBelowIt) {
    const std::string& method = GetParam();
    const Scene scene = overhangScene(false);
    const Layers ref = test::renderReference(scene);
    const Layers wall = test::renderWith(overhangScene(true), "shadow_map");
    const Layers got = test::renderWith(scene, method);
    const Image &rv = *ref.find("V"), &wm = *wall.find("mask"), &v = *got.find("V");
    int umbra = 0, dark = 0;
    for (size_t i = 0; i < rv.pixels.size(); ++i)
        if (wm.pixels[i] > 0.5f && rv.pixels[i] < 0.05f) ++umbra, dark += v.pixels[i] < 0.5f;
    test::dumpPng("overhang_" + method, v);
    std::printf("%s: %d of the wall's %d umbra pixels dark\n", method.c_str(), dark, umbra);
    ASSERT_GT(umbra, int(rv.pixels.size()) / 10) << "the wall's face must be in view and in the umbra";
    // Lit at every such pixel when the face is only tested at its own texel; the march's 24
    // points miss the 0.2 m slab where they straddle it (12 points found 27 %).
    EXPECT_GT(dark, umbra * 6 / 10) << method;
}

INSTANTIATE_TEST_SUITE_P(Methods, UnseenCentre,
                         ::testing::Values("shadow_map", "dbuffer", "penumbra_map", "pcss"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace ss
