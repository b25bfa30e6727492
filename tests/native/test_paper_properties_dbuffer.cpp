// Does dbuffer keep the paper's figure 8: the penumbra narrows as the occluder nears the
// receiver and widens with the light?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "softshadow/softshadow.h"
#include "test_pcss_support.h"

namespace ss::test {
namespace {

// A plate whose straight edge runs along y at x = -0.5, its underside at height h, over the
// ground; the light off to the -x side puts the edge's soft shadow beyond the plate as the top
// camera sees it. Theory (a disk of diameter D at height 4): penumbra width D h / (4 - h).
Scene edgeScene(float h, float diameter) {
    Scene s;
    s.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(makeBox({-6.0f, -6.0f, h}, {-0.5f, 6.0f, h + 0.1f}, SS_MESH_CAST));
    s.addLight(makeDiskLight({-3.0f, 0.0f, 4.0f}, diameter));
    s.setCamera(makeTopCamera());
    return s;
}

// Mean over the middle rows of the number of pixels with V in (0.05, 0.95): the penumbra's
// width along a row, in pixels (the edge is perpendicular to the rows).
double penumbraWidth(const Layers& l) {
    const Image& V = *l.find("V");
    const Image& mask = *l.find("mask");
    double sum = 0.0;
    int rows = 0;
    for (int y = V.height / 2 - 10; y < V.height / 2 + 10; ++y) {
        int n = 0;
        for (int x = 0; x < V.width; ++x)
            n += mask.at(x, y) > 0.5f && V.at(x, y) > 0.05f && V.at(x, y) < 0.95f;
        sum += n;
        ++rows;
    }
    return sum / rows;
}

struct Case {
    float h, diameter;
};

std::vector<double> widths(const std::vector<Case>& cases, const char* what) {
    std::vector<double> out;
    for (const Case& c : cases) {
        Scene scene = edgeScene(c.h, c.diameter);
        double w = penumbraWidth(renderWith(scene, "dbuffer"));
        double wr = penumbraWidth(renderReference(scene));
        std::printf("[dbuffer] figure 8 %s: h %.2f D %.2f: penumbra %.1f px (reference %.1f px, theory %.2f m)\n",
                    what, c.h, c.diameter, w, wr, c.diameter * c.h / (4.0f - c.h));
        // dbuffer's penumbra is slightly narrower than the reference's (measured 0.7-1.7 px):
        // the smoothstep of eq. 4 is darker than the truth near t = 0.
        EXPECT_NEAR(w, wr, std::max(1.5, 0.2 * wr)) << what << " h " << c.h << " D " << c.diameter;
        out.push_back(w);
    }
    return out;
}

TEST(PaperPropertiesDbuffer, Figure8PenumbraNarrowsAsTheOccluderNearsTheReceiver) {
    // The occluder comes down towards the ground: each step the theoretical width falls by
    // about half (0.9, 0.5, 0.21 m).
    std::vector<double> w = widths({{1.5f, 1.5f}, {1.0f, 1.5f}, {0.5f, 1.5f}}, "occluder height");
    for (size_t i = 1; i < w.size(); ++i) EXPECT_LT(w[i], 0.8 * w[i - 1]) << "step " << i;
    EXPECT_GT(w.back(), 0.5) << "the nearest occluder still has a penumbra";
}

TEST(PaperPropertiesDbuffer, Figure8PenumbraWidensWithTheLight) {
    // Width linear in the light's diameter: x2 per step (0.25, 0.5, 1.0 m).
    std::vector<double> w = widths({{1.0f, 0.75f}, {1.0f, 1.5f}, {1.0f, 3.0f}}, "light diameter");
    for (size_t i = 1; i < w.size(); ++i) EXPECT_GT(w[i], 1.4 * w[i - 1]) << "step " << i;
}

}  // namespace
}  // namespace ss::test
