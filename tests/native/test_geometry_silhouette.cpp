// Checks point and disk silhouettes on analytic shapes: exact edge and face sets, and the rules.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "geometry/silhouette.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

using EdgeSet = std::set<std::pair<uint32_t, uint32_t>>;  // undirected (lo, hi)

// Cube [-1,1]^3, outward CCW. Vertex i has x = bit0, y = bit1, z = bit2 (0 -> -1, 1 -> +1).
Mesh cube() {
    std::vector<glm::vec3> p;
    for (int i = 0; i < 8; ++i) p.push_back({i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f});
    auto quad = [](std::vector<glm::uvec3>& t, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
        t.push_back({a, b, c});
        t.push_back({a, c, d});
    };
    std::vector<glm::uvec3> t;
    quad(t, 0, 2, 3, 1);  // -z
    quad(t, 4, 5, 7, 6);  // +z
    quad(t, 0, 1, 5, 4);  // -y
    quad(t, 2, 6, 7, 3);  // +y
    quad(t, 0, 4, 6, 2);  // -x
    quad(t, 1, 3, 7, 5);  // +x
    return test::makeMesh(p, t);
}

Mesh tetrahedron() {
    return test::makeMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                     {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}
// Faces of tetrahedron(): 0 bottom (z=0), 1 y=0, 2 x=0, 3 slanted.

Mesh uvSphere(int rings, int segments) {
    Mesh m = test::makeUvSphere({0, 0, 0}, 1.0f, rings, segments, SS_MESH_CAST | SS_MESH_RECEIVE);
    m.name = "test";
    return m;
}

EdgeSet undirected(const std::vector<SilhouetteEdge>& edges) {
    EdgeSet s;
    for (const SilhouetteEdge& e : edges) s.insert({std::min(e.a, e.b), std::max(e.a, e.b)});
    return s;
}

// Every vertex of a simple closed loop starts exactly one edge and ends exactly one.
void expectOrientedLoops(const std::vector<SilhouetteEdge>& edges) {
    std::map<uint32_t, int> starts, ends;
    for (const SilhouetteEdge& e : edges) ++starts[e.a], ++ends[e.b];
    for (auto [v, n] : starts) EXPECT_EQ(n, 1) << "vertex " << v;
    for (auto [v, n] : ends) EXPECT_EQ(n, 1) << "vertex " << v;
    EXPECT_EQ(starts.size(), ends.size());
}

TEST(PointSilhouette, CubeFromCornerDirectionIsAHexagon) {
    Mesh m = cube();
    PointSilhouette s = pointSilhouette(m, {10, 10, 10});
    // Front: +x, +y, +z (2 triangles each). Silhouette: the 6 edges around them that do not
    // touch vertex 7 (the corner facing the point) and are not the cube's far edges.
    int front = 0;
    for (uint8_t f : s.frontFacing) front += f;
    EXPECT_EQ(front, 6);
    EdgeSet expected = {{1, 3}, {2, 3}, {2, 6}, {4, 6}, {4, 5}, {1, 5}};
    EXPECT_EQ(undirected(s.edges), expected);
    ASSERT_EQ(s.vertices.size(), 6u);
    for (const SilhouetteVertex& v : s.vertices) EXPECT_EQ(v.edges.size(), 2u);
    expectOrientedLoops(s.edges);
    for (const SilhouetteEdge& e : s.edges) {
        EXPECT_TRUE(s.frontFacing[e.face]);
        EXPECT_FALSE(s.frontFacing[e.otherFace]);
    }
}

TEST(PointSilhouette, CubeFromAboveIsTheTopSquareAndDiagonalsNeverCount) {
    Mesh m = cube();
    PointSilhouette s = pointSilhouette(m, {0.1f, 0.2f, 5});
    EXPECT_EQ(undirected(s.edges), (EdgeSet{{4, 5}, {5, 7}, {6, 7}, {4, 6}}));
    expectOrientedLoops(s.edges);
    // Oriented counter-clockwise seen from above (+z), as the top face walks them.
    glm::vec3 turn(0.0f);
    for (const SilhouetteEdge& e : s.edges) turn += glm::cross(m.objectPositions[e.a], m.objectPositions[e.b]);
    EXPECT_GT(turn.z, 0.0f);
}

TEST(PointSilhouette, PointInAFacePlaneSeesItAsBackFacing) {
    Mesh m = cube();
    // On the plane z = 1 (top face) and outside x = 1 (the +x face is front).
    PointSilhouette s = pointSilhouette(m, {5, 0, 1});
    EXPECT_FALSE(s.frontFacing[2]);
    EXPECT_FALSE(s.frontFacing[3]);
    EXPECT_TRUE(s.frontFacing[10]);
    EXPECT_EQ(undirected(s.edges), (EdgeSet{{1, 3}, {3, 7}, {5, 7}, {1, 5}}));
}

TEST(PointSilhouette, OpenQuadEdgesCountFromBothSides) {
    Mesh m = test::makeMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
    EdgeSet border = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
    PointSilhouette above = pointSilhouette(m, {0.5f, 0.5f, 3});
    PointSilhouette below = pointSilhouette(m, {0.5f, 0.5f, -3});
    EXPECT_EQ(undirected(above.edges), border);
    EXPECT_EQ(undirected(below.edges), border);
    expectOrientedLoops(above.edges);
    expectOrientedLoops(below.edges);
    // Turned towards the point: counter-clockwise seen from the point in both cases.
    auto turnZ = [&](const PointSilhouette& s) {
        float z = 0;
        for (const SilhouetteEdge& e : s.edges) z += glm::cross(m.objectPositions[e.a] - glm::vec3(0.5f, 0.5f, 0), m.objectPositions[e.b] - glm::vec3(0.5f, 0.5f, 0)).z;
        return z;
    };
    EXPECT_GT(turnZ(above), 0.0f);
    EXPECT_LT(turnZ(below), 0.0f);
    for (const SilhouetteEdge& e : above.edges) EXPECT_EQ(e.otherFace, kNoFace);
}

TEST(PointSilhouette, NonManifoldFinNeedsBothClassesAmongItsFaces) {
    // Three triangles on edge (0,1): two facing +z-ish, one facing +y.
    Mesh m = test::makeMesh({{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}},
                       {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
    ASSERT_EQ(m.report.nonManifoldEdges, 1u);
    // From high above: faces 0 and 1 front (+z), face 2 normal -y: the point at y=0.5 is
    // behind it. The fin edge has both classes: silhouette.
    PointSilhouette s = pointSilhouette(m, {0.5f, 0.5f, 5});
    EXPECT_TRUE(s.frontFacing[0]);
    EXPECT_FALSE(s.frontFacing[2]);
    EXPECT_EQ(undirected(s.edges).count({0, 1}), 1u);
    // From y=-5, z=0.1: face 2 front (normal -y), face 1 (normal +z? no: 1,0,3 winds -z) ...
    // whatever their facing, the rule is: silhouette iff both classes are present.
    PointSilhouette t = pointSilhouette(m, {0.5f, -5, 0.1f});
    bool mixed = !(t.frontFacing[0] == t.frontFacing[1] && t.frontFacing[1] == t.frontFacing[2]);
    EXPECT_EQ(undirected(t.edges).count({0, 1}), mixed ? 1u : 0u);
}

TEST(PointSilhouette, DegenerateFacesTakeNoPart) {
    // A tetrahedron plus a zero-area triangle hanging on one of its edges by a duplicate vertex.
    Mesh m = test::makeMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5f, 0, 0}},
                       {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 1}});
    ASSERT_EQ(m.report.degenerateFaces, 1u);
    PointSilhouette s = pointSilhouette(m, {0.2f, 0.2f, 5});
    EXPECT_FALSE(s.frontFacing[4]);
    // Edge (0,1) has faces 0 (bottom, back) and 1 (y=0: back from y=0.2) and the degenerate one:
    // not a silhouette. Silhouette from above: the slanted face's... the edges between back
    // faces and the front faces (slanted, face 3): (1,2),(1,3),(2,3).
    EXPECT_EQ(undirected(s.edges), (EdgeSet{{1, 2}, {1, 3}, {2, 3}}));
}

// ---- disk --------------------------------------------------------------------------------

Disk disk(glm::vec3 c, float r) { return Disk{c, {0, 0, -1}, r}; }

TEST(DiskSilhouette, ExtremesMaximiseAndMinimiseTheSignedDistance) {
    Disk d = disk({0, 0, 5}, 2);
    glm::vec3 n = glm::normalize(glm::vec3(1, 0, 1));
    DiskExtremes x = diskExtremes(n, d);
    EXPECT_FALSE(x.parallel);
    EXPECT_NEAR(x.pNear.x, 2.0f, 1e-6f);
    EXPECT_NEAR(x.pFar.x, -2.0f, 1e-6f);
    DiskExtremes p = diskExtremes({0, 0, 1}, d);
    EXPECT_TRUE(p.parallel);
    EXPECT_EQ(p.pNear, d.centre);
}

TEST(DiskSilhouette, SmallDiskOverCubeGivesTopSquareForBoth) {
    Mesh m = cube();
    DiskSilhouette s = diskSilhouette(m, disk({0, 0, 5}, 0.5f));
    EdgeSet top = {{4, 5}, {5, 7}, {6, 7}, {4, 6}};
    EXPECT_EQ(undirected(s.umbraEdges), top);
    EXPECT_EQ(undirected(s.penumbraEdges), top);
    EXPECT_TRUE(s.silhouetteFacesCentreBack.empty());
    EXPECT_TRUE(s.silhouetteFacesCentreFront.empty());
    EXPECT_EQ(s.faces[2], DiskFacing::AllFront);  // parallel face, centre in front
    EXPECT_EQ(s.faces[0], DiskFacing::NoneFront);  // parallel face, centre behind
    expectOrientedLoops(s.umbraEdges);
    expectOrientedLoops(s.penumbraEdges);
}

TEST(DiskSilhouette, WideDiskOverCubeMakesSidesSilhouetteFaces) {
    Mesh m = cube();
    DiskSilhouette s = diskSilhouette(m, disk({0, 0, 5}, 2));
    EXPECT_EQ(undirected(s.umbraEdges), (EdgeSet{{0, 1}, {1, 3}, {2, 3}, {0, 2}}));  // bottom
    EXPECT_EQ(undirected(s.penumbraEdges), (EdgeSet{{4, 5}, {5, 7}, {6, 7}, {4, 6}}));  // top
    EXPECT_EQ(s.silhouetteFacesCentreBack, (std::vector<uint32_t>{4, 5, 6, 7, 8, 9, 10, 11}));
    EXPECT_TRUE(s.silhouetteFacesCentreFront.empty());
    ASSERT_EQ(s.umbraVertices.size(), 4u);
    for (const SilhouetteVertex& v : s.umbraVertices) EXPECT_EQ(v.edges.size(), 2u);
    expectOrientedLoops(s.umbraEdges);
}

TEST(DiskSilhouette, TetrahedronAtThreeDiskSizes) {
    Mesh m = tetrahedron();
    glm::vec3 c(0.2f, 0.2f, 3);
    EdgeSet bottom = {{0, 1}, {0, 2}, {1, 2}}, slanted = {{1, 2}, {1, 3}, {2, 3}};
    {  // r = 0.1: x=0 and y=0 faces see none of it (s = r - 0.2 < 0)
        DiskSilhouette s = diskSilhouette(m, disk(c, 0.1f));
        EXPECT_EQ(s.faces[3], DiskFacing::AllFront);
        EXPECT_EQ(undirected(s.umbraEdges), slanted);
        EXPECT_EQ(undirected(s.penumbraEdges), slanted);
    }
    {  // r = 1: the x=0 and y=0 faces become silhouette faces (centre behind them)
        DiskSilhouette s = diskSilhouette(m, disk(c, 1.0f));
        EXPECT_EQ(s.faces[3], DiskFacing::AllFront);
        EXPECT_EQ(undirected(s.umbraEdges), bottom);
        EXPECT_EQ(undirected(s.penumbraEdges), slanted);
        EXPECT_EQ(s.silhouetteFacesCentreBack, (std::vector<uint32_t>{1, 2}));
        EXPECT_TRUE(s.silhouetteFacesCentreFront.empty());
    }
    {  // r = 2: s(pFar) of the slanted face = (2.4 - 2√2)/√3 < 0: silhouette face, centre front
        DiskSilhouette s = diskSilhouette(m, disk(c, 2.0f));
        EXPECT_EQ(undirected(s.umbraEdges), bottom);
        EXPECT_TRUE(s.penumbraEdges.empty());
        EXPECT_EQ(s.silhouetteFacesCentreBack, (std::vector<uint32_t>{1, 2}));
        EXPECT_EQ(s.silhouetteFacesCentreFront, (std::vector<uint32_t>{3}));
    }
}

// The signed distance over a disk is extreme on its rim: dense rim sampling is the brute force.
DiskFacing bruteForce(const Mesh& m, uint32_t f, const Disk& d, float* margin) {
    glm::vec3 n = m.faceNormals[f], v0 = m.objectPositions[m.triangles[f][0]];
    glm::vec3 u = glm::normalize(glm::cross(d.normal, std::abs(d.normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
    glm::vec3 w = glm::cross(d.normal, u);
    float lo = 1e30f, hi = -1e30f;
    for (int k = 0; k < 1024; ++k) {
        float a = 2.0f * float(M_PI) * k / 1024;
        float s = glm::dot(n, d.centre + d.radius * (std::cos(a) * u + std::sin(a) * w) - v0);
        lo = std::min(lo, s), hi = std::max(hi, s);
    }
    *margin = std::min(std::abs(lo), std::abs(hi));
    if (hi <= 0) return DiskFacing::NoneFront;
    if (lo > 0) return DiskFacing::AllFront;
    return glm::dot(n, d.centre - v0) > 0 ? DiskFacing::SilhouetteCentreFront : DiskFacing::SilhouetteCentreBack;
}

TEST(DiskSilhouette, SphereFacesMatchRimSamplingForTiltedDisks) {
    Mesh m = uvSphere(24, 32);
    int checked = 0;
    for (glm::vec3 c : {glm::vec3(0, 0, 4), glm::vec3(3, 1, 2), glm::vec3(-2, 2, -3)})
        for (float r : {0.3f, 1.5f, 4.0f}) {
            Disk d{c, glm::normalize(-c + glm::vec3(0.3f, 0, 0)), r};
            DiskSilhouette s = diskSilhouette(m, d);
            for (uint32_t f = 0; f < m.triangles.size(); ++f) {
                float margin;
                DiskFacing expect = bruteForce(m, f, d, &margin);
                // Rim sampling at 1024 points misses the extreme by at most r(1-cos(π/1024)) ≈ 5e-6 r (r ≤ 4);
                // skip faces whose extreme is that close to the plane.
                if (margin < 1e-4f) continue;
                EXPECT_EQ(int(s.faces[f]), int(expect)) << "face " << f;
                ++checked;
            }
        }
    EXPECT_GT(checked, 10000);
}

TEST(DiskSilhouette, SphereUnderAxisDiskHasLatitudeLoops) {
    // Rings of 16 latitude bands; disk on the axis at z = 4 radius 2 facing down. A face sees the
    // whole disk when its plane lies below every rim point; by symmetry the classes are whole
    // latitude bands, so each silhouette is exactly one full ring of 32 edges.
    const int rings = 16, segments = 32;
    Mesh m = uvSphere(rings, segments);
    DiskSilhouette s = diskSilhouette(m, disk({0, 0, 4}, 2));
    ASSERT_EQ(s.umbraEdges.size(), size_t(segments));
    ASSERT_EQ(s.penumbraEdges.size(), size_t(segments));
    expectOrientedLoops(s.umbraEdges);
    expectOrientedLoops(s.penumbraEdges);
    auto ringZ = [&](const std::vector<SilhouetteEdge>& es) {
        float z = m.objectPositions[es[0].a].z;
        for (const SilhouetteEdge& e : es) {
            EXPECT_FLOAT_EQ(m.objectPositions[e.a].z, z);
            EXPECT_FLOAT_EQ(m.objectPositions[e.b].z, z);
        }
        return z;
    };
    float zu = ringZ(s.umbraEdges), zp = ringZ(s.penumbraEdges);
    // Penumbra silhouette (the all-frontfacing cap's border) lies above the umbra one; for a
    // smooth sphere the tangent cones from the disk rim touch at z = 1/4 ± (r/4)·√(1 - 1/16)
    // ... the mesh bands are 11.25° wide, so compare with the bands containing those angles.
    EXPECT_GT(zp, zu);
    // Between them every face is a silhouette face (centre-front above the centre's own
    // horizon z = 1/4, centre-back below it).
    for (uint32_t f : s.silhouetteFacesCentreFront) {
        float z = 0;
        for (int k = 0; k < 3; ++k) z += m.objectPositions[m.triangles[f][k]].z / 3;
        EXPECT_LT(z, zp + 1e-5f);
        EXPECT_GT(z, zu - 1e-5f);
    }
    EXPECT_EQ(s.silhouetteFacesCentreFront.size() % segments, 0u);
    EXPECT_EQ(s.silhouetteFacesCentreBack.size() % segments, 0u);
    EXPECT_FALSE(s.silhouetteFacesCentreFront.empty());
    EXPECT_FALSE(s.silhouetteFacesCentreBack.empty());
}

TEST(DiskSilhouette, OpenQuadIsBothUmbraAndPenumbraSilhouette) {
    Mesh m = test::makeMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
    EdgeSet border = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
    for (float z : {3.0f, -3.0f}) {
        DiskSilhouette s = diskSilhouette(m, Disk{{0.5f, 0.5f, z}, {0, 0, z > 0 ? -1.f : 1.f}, 0.5f});
        EXPECT_EQ(undirected(s.umbraEdges), border);
        EXPECT_EQ(undirected(s.penumbraEdges), border);
        expectOrientedLoops(s.umbraEdges);
        // Umbra and penumbra run the same way round.
        for (size_t i = 0; i < s.umbraEdges.size(); ++i) {
            auto it = std::find_if(s.penumbraEdges.begin(), s.penumbraEdges.end(),
                                   [&](const SilhouetteEdge& p) { return p.edge == s.umbraEdges[i].edge; });
            ASSERT_NE(it, s.penumbraEdges.end());
            EXPECT_EQ(it->a, s.umbraEdges[i].a);
        }
    }
}

}  // namespace
}  // namespace ss
