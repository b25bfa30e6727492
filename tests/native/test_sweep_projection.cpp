// Do projected silhouette edges give the same hard shadow as the union of every projected
// front face (Clipper), for random closed meshes and light positions, and does a torus keep
// its hole?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>
#include <polyclipping/clipper.hpp>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "methods/sweep/projection.h"
#include "methods/sweep/receiver.h"
#include "planar/outline.h"
#include "planar/trapezoids.h"
#include "test_scenes.h"

using namespace ss;

namespace {

// A closed, outward-wound UV sphere with radial noise (star-shaped, often concave).
Mesh makeBumpySphere(std::mt19937& rng, const glm::vec3& centre, float radius, int rings, int segs) {
    std::uniform_real_distribution<float> bump(0.7f, 1.3f);
    Mesh m;
    m.name = "bumpy";
    m.objectPositions.push_back(centre + glm::vec3(0, 0, -radius * bump(rng)));
    for (int i = 1; i < rings; ++i) {
        float th = float(M_PI) * i / rings;
        for (int j = 0; j < segs; ++j) {
            float ph = 2.0f * float(M_PI) * j / segs, r = radius * bump(rng);
            m.objectPositions.push_back(centre + r * glm::vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), -std::cos(th)));
        }
    }
    m.objectPositions.push_back(centre + glm::vec3(0, 0, radius * bump(rng)));
    auto at = [&](int i, int j) { return uint32_t(1 + (i - 1) * segs + (j % segs)); };
    uint32_t top = uint32_t(m.objectPositions.size() - 1);
    for (int j = 0; j < segs; ++j) m.triangles.push_back({0, at(1, j + 1), at(1, j)});
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < segs; ++j) {
            m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    for (int j = 0; j < segs; ++j) m.triangles.push_back({top, at(rings - 1, j), at(rings - 1, j + 1)});
    m.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    m.finalize();
    return m;
}

Mesh rotated(Mesh m, const glm::mat4& xf) {
    for (glm::vec3& p : m.objectPositions) p = glm::vec3(xf * glm::vec4(p, 1.0f));
    m.finalize();
    return m;
}

struct Case {
    double outlineArea = 0, clipperArea = 0, perimeter = 0;
    size_t holes = 0;
};

// Our silhouette path vs Clipper's union of every front face projected independently here.
Case runCase(const Scene& scene, const LightSample& sample) {
    const Light& light = scene.lights()[0];
    ReceiverPlane plane = findReceiverPlane(scene, light, "");
    planar::Snap snap(plane.cu, plane.cv, plane.half);
    std::vector<int> occ = sweepOccluders(scene, 0, plane);
    std::vector<planar::DirectedEdge> edges;
    projectSample(scene, occ, plane, snap, sample, &edges, nullptr);
    std::vector<planar::Chain> chains = planar::linkChains(planar::hardOutline(edges));
    Case c;
    c.outlineArea = planar::regionArea(chains);
    for (const auto& ch : chains) c.holes += planar::twiceSignedArea(ch) > 0;

    ClipperLib::Paths tris;
    double hs = plane.height(sample.point);
    for (int mi : occ) {
        const Mesh& m = scene.meshes()[mi];
        for (const glm::uvec3& t : m.triangles) {
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k) p[k] = glm::dvec3(m.objectPositions[t[k]]);
            if (glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), sample.point - p[0]) <= 0) continue;
            ClipperLib::Path path;
            for (int k = 0; k < 3; ++k) {
                glm::dvec3 q = sample.point + (p[k] - sample.point) * (hs / (hs - plane.height(p[k])));
                glm::dvec2 uv = plane.toPlane(q);
                path.push_back(ClipperLib::IntPoint(std::llround((uv.x - plane.cu) * snap.scale()),
                                                    std::llround((uv.y - plane.cv) * snap.scale())));
            }
            for (int k = 0; k < 3; ++k)
                c.perimeter += std::hypot(double(path[k].X - path[(k + 1) % 3].X), double(path[k].Y - path[(k + 1) % 3].Y));
            tris.push_back(path);
        }
    }
    ClipperLib::Clipper cl;
    cl.AddPaths(tris, ClipperLib::ptSubject, true);
    ClipperLib::Paths out;
    cl.Execute(ClipperLib::ctUnion, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    for (const auto& p : out) c.clipperArea += ClipperLib::Area(p);
    c.clipperArea = std::fabs(c.clipperArea);
    return c;
}

Scene sceneWith(Mesh occluder) {
    Scene s;
    s.addMesh(test::makeGround(30.0f, 0.0f, SS_MESH_RECEIVE));
    s.addMesh(std::move(occluder));
    s.addLight(test::makeDiskLight({0, 0, 10}, 1.0f));
    return s;
}

}  // namespace

// Tolerance: every projected vertex is rounded to the grid on both sides (< 0.71 units each),
// and crossing points once more by us and once by Clipper, so the areas differ by at most about
// 0.71 * 2 * (sum of front-face perimeters, which bounds the outline's) grid units^2.
TEST(SweepProjection, RandomMeshesAndLightsMatchClipperUnionOfFrontFaces) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> pos(-1.5f, 1.5f), ang(0.0f, 6.2831853f), height(3.0f, 9.0f);
    const int cases = test::quickTests() ? 60 : 300;
    for (int c = 0; c < cases; ++c) {
        Mesh occ;
        glm::mat4 xf = glm::rotate(glm::mat4(1.0f), ang(rng), glm::normalize(glm::vec3(pos(rng), pos(rng), 1.0f)));
        xf = glm::translate(glm::mat4(1.0f), glm::vec3(pos(rng), pos(rng), 1.5f)) * xf;
        switch (c % 3) {
            case 0: occ = makeBumpySphere(rng, {0, 0, 0}, 0.8f, 8, 12); break;
            case 1: occ = test::makeTorus({0, 0, 0}, 0.8f, 0.25f, 16, 8, SS_MESH_CAST); break;
            default: occ = test::makeBox({-0.5f, -0.4f, -0.3f}, {0.5f, 0.4f, 0.3f}, SS_MESH_CAST); break;
        }
        occ = rotated(std::move(occ), xf);
        ASSERT_TRUE(usesSilhouettes(occ));
        Scene s = sceneWith(std::move(occ));
        LightSample sample;
        sample.point = glm::dvec3(pos(rng) * 2, pos(rng) * 2, height(rng));
        Case r = runCase(s, sample);
        ASSERT_GT(r.clipperArea, 0.0);
        EXPECT_NEAR(r.outlineArea, r.clipperArea, 1.5 * r.perimeter + 1e-9 * r.clipperArea) << "case " << c;
    }
}

TEST(SweepProjection, TorusShadowKeepsItsHole) {
    Scene s = sceneWith(test::makeTorus({0, 0, 1.5f}, 1.0f, 0.25f, 32, 12, SS_MESH_CAST));
    LightSample sample;
    sample.point = {0.2, 0.1, 6.0};
    Case r = runCase(s, sample);
    EXPECT_EQ(r.holes, 1u);
    EXPECT_NEAR(r.outlineArea, r.clipperArea, 1.5 * r.perimeter);
}

TEST(SweepProjection, OpenMeshFallsBackToFrontTriangles) {
    // The ground itself is open; as an occluder above another ground it casts its square.
    Scene s;
    s.addMesh(test::makeGround(30.0f, 0.0f, SS_MESH_RECEIVE));
    Mesh quad = test::makeGround(1.0f, 1.0f, SS_MESH_CAST);
    quad.name = "card";
    EXPECT_FALSE(usesSilhouettes(quad));
    s.addMesh(quad);
    s.addLight(test::makeDiskLight({0, 0, 10}, 1.0f));
    LightSample sample;
    sample.point = {0, 0, 2.0};
    Case r = runCase(s, sample);
    // A square of side 2 at height 1, light at height 2: the shadow has side 4.
    ReceiverPlane plane = findReceiverPlane(s, s.lights()[0], "");
    double scale = planar::Snap(plane.cu, plane.cv, plane.half).scale();
    EXPECT_NEAR(r.outlineArea / (scale * scale), 16.0, 16.0 * 1e-5);
}

TEST(SweepProjection, ReceiverIsLargestPlanarReceiverOrTheNamedOne) {
    Scene s = test::sceneBox();
    const Light& l = s.lights()[0];
    ReceiverPlane p = findReceiverPlane(s, l, "");
    EXPECT_TRUE(s.meshes()[p.mesh].receives());
    EXPECT_NEAR(p.normal.z, 1.0, 1e-12);  // towards the light
    EXPECT_THROW(findReceiverPlane(s, l, "no such mesh"), Error);
}
