// Does penumbra_map keep the paper's figure 6: where two penumbrae overlap, the darkest wins?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "softshadow/softshadow.h"
#include "test_pcss_support.h"

namespace ss::test {
namespace {

// Two plates side by side under a wide disk: their hard shadows are apart, their outer
// penumbrae (each L_r (Z_P - Z_V)/Z_V = 0.64 wide) overlap in a band 0.4 wide between them.
Scene twoPlates(bool left, bool right) {
    Scene s;
    s.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    if (left) s.addMesh(makeBox({-1.6f, -2.0f, 1.1f}, {-0.3f, 2.0f, 1.2f}, SS_MESH_CAST));
    if (right) s.addMesh(makeBox({0.3f, -2.0f, 1.1f}, {1.6f, 2.0f, 1.2f}, SS_MESH_CAST));
    s.addLight(makeDiskLight({0.0f, 0.0f, 4.0f}, 3.0f));
    s.setCamera(makeTopCamera());
    return s;
}

TEST(PaperPropertiesPenumbraMap, DarkestWinsWhereTwoPenumbraeOverlap) {
    Layers both = renderWith(twoPlates(true, true), "penumbra_map");
    Layers left = renderWith(twoPlates(true, false), "penumbra_map");
    Layers right = renderWith(twoPlates(false, true), "penumbra_map");
    Layers ref = renderReference(twoPlates(true, true));
    const Image &vb = *both.find("V"), &vl = *left.find("V"), &vr = *right.find("V"), &vref = *ref.find("V");
    const Image &mb = *both.find("mask"), &ml = *left.find("mask"), &mr = *right.find("mask");
    size_t overlap = 0, within = 0, belowProduct = 0;
    double maxDiff = 0.0, sumDiff = 0.0, sumRefGap = 0.0;
    for (size_t i = 0; i < vb.pixels.size(); ++i) {
        if (mb.pixels[i] < 0.5f || ml.pixels[i] < 0.5f || mr.pixels[i] < 0.5f) continue;
        float a = vl.pixels[i], b = vr.pixels[i];
        // Overlap: in both penumbrae (neither occluder alone leaves it lit or in its umbra).
        if (!(a > 0.05f && a < 0.95f && b > 0.05f && b < 0.95f)) continue;
        ++overlap;
        double expected = std::min(a, b);
        double diff = std::abs(double(vb.pixels[i]) - expected);
        maxDiff = std::max(maxDiff, diff);
        sumDiff += diff;
        within += diff <= 0.02;
        // Not a product or a sum: where both dim the light, the minimum is brighter than a*b.
        belowProduct += double(vb.pixels[i]) > double(a) * double(b) + 0.05;
        sumRefGap += double(vb.pixels[i]) - double(vref.pixels[i]);
    }
    std::printf("[penumbra_map] figure 6 overlap: %zu px, |V - min(V_left, V_right)| mean %.4f max %.4f, "
                "%zu px within 0.02; %zu px brighter than the product by > 0.05; mean V - reference %.3f\n",
                overlap, overlap ? sumDiff / double(overlap) : 0.0, maxDiff, within, belowProduct,
                overlap ? sumRefGap / double(overlap) : 0.0);
    ASSERT_GT(overlap, 150u) << "the two penumbrae must overlap in the image";
    // Each texel of the penumbra map keeps the darkest of the two occluders' cone/sheet values,
    // and the camera pass reads one texel: V is the minimum, up to the 8-neighbour rule at the
    // hard edges (none in the overlap) and float rounding.
    EXPECT_GE(double(within), 0.99 * double(overlap));
    EXPECT_LT(sumDiff / double(overlap), 0.005);
    // The rule is the minimum, not the product: the test can tell the two apart here.
    EXPECT_GT(double(belowProduct), 0.3 * double(overlap));
    // The paper's choice is brighter than the truth, where both occluders remove light.
    EXPECT_GT(sumRefGap / double(overlap), 0.0);
}

}  // namespace
}  // namespace ss::test
