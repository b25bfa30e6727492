// What dbuffer does in the failure cases the paper admits (§4): no umbra when the light is
// larger than the occluder, and acute silhouette corners, measured against the reference.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "softshadow/softshadow.h"
#include "test_pcss_support.h"

namespace ss::test {
namespace {

// Where pixel (x, y)'s ray meets the ground z = 0 (the camera looks down on it).
glm::vec3 groundPoint(const Camera& cam, int x, int y) {
    Ray r = cam.pixelRay(float(x) + 0.5f, float(y) + 0.5f);
    float s = -r.origin.z / r.direction.z;
    return r.origin + s * r.direction;
}

struct RegionStats {
    int pixels = 0;
    double sum = 0.0, refSum = 0.0, absErr = 0.0;
    int methodUmbra = 0, refUmbra = 0;
};

// Statistics over the masked pixels whose ground point satisfies `inside`.
template <class Inside>
RegionStats region(const Scene& scene, const Layers& l, const Layers& ref, Inside inside) {
    const Image& V = *l.find("V");
    const Image& R = *ref.find("V");
    const Image& mask = *ref.find("mask");
    RegionStats s;
    for (int y = 0; y < V.height; ++y)
        for (int x = 0; x < V.width; ++x) {
            if (!(mask.at(x, y) > 0.5f) || !inside(groundPoint(scene.camera(), x, y))) continue;
            ++s.pixels;
            s.sum += V.at(x, y);
            s.refSum += R.at(x, y);
            s.absErr += std::abs(V.at(x, y) - R.at(x, y));
            s.methodUmbra += V.at(x, y) < 0.05f;
            s.refUmbra += R.at(x, y) < 0.05f;
        }
    return s;
}

// Failure case 2 of §4: "the light source is much larger than the occluder": a 0.3 m box at
// 1.5 m under a 3 m disk at 4 m. From the ground the box subtends about 0.2 rad and the light
// 0.7 rad, so no ground point is in umbra; the paper says eq. 4 then gives values too low.
TEST(PaperFailuresDbuffer, NoUmbraWhenTheLightIsLargerThanTheOccluder) {
    Scene scene;
    scene.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addMesh(makeBox({-0.15f, -0.15f, 1.45f}, {0.15f, 0.15f, 1.55f}, SS_MESH_CAST));
    scene.addLight(makeDiskLight({0.0f, 0.0f, 4.0f}, 3.0f));
    scene.setCamera(makeTopCamera());
    Layers ref = renderReference(scene);
    Layers dbuf = renderWith(scene, "dbuffer");
    Layers root = renderWith(scene, "dbuffer", {{"small_occluders", "true"}});
    auto shadow = [](const glm::vec3& p) { return std::abs(p.x) < 0.6f && std::abs(p.y) < 0.6f; };
    RegionStats d = region(scene, dbuf, ref, shadow), r = region(scene, root, ref, shadow);
    Metrics md = compareToReference(dbuf, ref), mr = compareToReference(root, ref);
    std::printf("[dbuffer] no umbra: %d px under the box; reference mean V %.3f, %d umbra px; smoothstep mean %.3f, "
                "%d umbra px, mean |err| %.3f, RMSE %.4f; sqrt(t) mean %.3f, %d umbra px, mean |err| %.3f, RMSE %.4f\n",
                d.pixels, d.refSum / d.pixels, d.refUmbra, d.sum / d.pixels, d.methodUmbra, d.absErr / d.pixels,
                md.rmse, r.sum / r.pixels, r.methodUmbra, r.absErr / r.pixels, mr.rmse);
    ASSERT_GT(d.pixels, 100);
    EXPECT_EQ(d.refUmbra, 0) << "the scene must have no umbra";
    // What happens, in the paper's words "values that are too low": measured mean V 0.62
    // against the reference's 0.90 under the box (mean error 0.28), yet no pixel painted as umbra
    // (the umbra volume closes above the ground). The paper's alternative, sqrt(t), halves the
    // error (mean V 0.76, error 0.14).
    EXPECT_EQ(d.methodUmbra, 0);
    EXPECT_LT(d.sum / d.pixels, d.refSum / d.pixels - 0.15) << "no longer too dark: update the doc";
    EXPECT_GT(d.absErr / d.pixels, 0.15);
    EXPECT_LT(r.absErr / r.pixels, 0.7 * d.absErr / d.pixels) << "sqrt(t) no longer closer";
    EXPECT_GT(r.sum / r.pixels, d.sum / d.pixels);
}

// Failure case 3 of §4: acute silhouette corners. A plate shaped as a thin isosceles triangle
// (15° at its tip) at 1 m under a 1.5 m disk at 4 m: the error around the tip's shadow against
// the error along the middle of its long sides.
TEST(PaperFailuresDbuffer, AcuteCornersAreWorseThanStraightEdges) {
    std::vector<glm::vec2> wedge = {{1.2f, 0.0f}, {-0.8f, 0.27f}, {-0.8f, -0.27f}};
    Scene scene;
    scene.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addMesh(makePrism(wedge, 0, 1.0f, 1.1f, SS_MESH_CAST));
    scene.addLight(makeDiskLight({0.0f, 0.0f, 4.0f}, 1.5f));
    scene.setCamera(makeTopCamera());
    Layers ref = renderReference(scene);
    Layers dbuf = renderWith(scene, "dbuffer");
    // Hard-shadow outline from the centre: the plate's top scaled by 4 / (4 - 1.1).
    const float k = 4.0f / 2.9f;
    glm::vec2 tip = k * wedge[0], side = k * 0.5f * (wedge[0] + wedge[1]);
    auto near = [](glm::vec2 c) {
        return [c](const glm::vec3& p) { return glm::length(glm::vec2(p) - c) < 0.35f; };
    };
    RegionStats t = region(scene, dbuf, ref, near(tip));
    RegionStats s = region(scene, dbuf, ref, near(side));
    Metrics m = compareToReference(dbuf, ref);
    std::printf("[dbuffer] acute corner: tip %d px mean |err| %.3f (mean V %.3f vs ref %.3f), side %d px mean |err| "
                "%.3f (mean V %.3f vs ref %.3f); whole RMSE %.4f\n",
                t.pixels, t.absErr / t.pixels, t.sum / t.pixels, t.refSum / t.pixels, s.pixels, s.absErr / s.pixels,
                s.sum / s.pixels, s.refSum / s.pixels, m.rmse);
    ASSERT_GT(t.pixels, 50);
    ASSERT_GT(s.pixels, 50);
    // What happens: around the tip dbuffer is too dark (measured mean V 0.86 against 0.96, mean
    // error 0.098), twice the error along the straight sides (0.044), where it is close.
    EXPECT_GT(t.absErr / t.pixels, 1.5 * s.absErr / s.pixels);
    EXPECT_LT(t.sum / t.pixels, t.refSum / t.pixels - 0.05) << "the tip is no longer too dark: update the doc";
    EXPECT_LT(m.rmse, 0.03);
}

}  // namespace
}  // namespace ss::test
