// Checks that edge adjacency and the mesh report find open, non-manifold, flipped and degenerate input.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/mesh.h"
#include "core/scene.h"

namespace ss {
namespace {

// A unit tetrahedron with every face wound counter-clockwise seen from outside.
Mesh tetrahedron() {
    Mesh m;
    m.name = "tet";
    m.objectPositions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    m.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    return m;
}

TEST(MeshAdjacency, ClosedTetrahedronHasSixManifoldEdges) {
    Mesh m = tetrahedron();
    m.finalize();
    ASSERT_EQ(m.adjacency.edges.size(), 6u);
    for (const Edge& e : m.adjacency.edges) {
        EXPECT_TRUE(e.isManifold());
        EXPECT_TRUE(e.isConsistent());
        EXPECT_LT(e.v0, e.v1);
    }
    EXPECT_TRUE(m.report.closedManifold());
    EXPECT_EQ(m.report.degenerateFaces, 0u);
    // Every face's three edges point back at the face.
    for (uint32_t f = 0; f < m.triangles.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const Edge& e = m.adjacency.edges[m.adjacency.faceEdges[f][k]];
            EXPECT_TRUE(e.faces[0] == f || e.faces[1] == f);
        }
    // Outward normal of face {1,2,3} points along (1,1,1).
    EXPECT_NEAR(glm::dot(m.faceNormals[3], glm::normalize(glm::vec3(1))), 1.0f, 1e-6f);
}

TEST(MeshAdjacency, OpenMeshReportsItsBoundary) {
    Mesh m = tetrahedron();
    m.triangles.pop_back();  // remove one face: its three edges become open
    m.finalize();
    EXPECT_EQ(m.report.openEdges, 3u);
    EXPECT_EQ(m.report.nonManifoldEdges, 0u);
    EXPECT_FALSE(m.report.closedManifold());
}

TEST(MeshAdjacency, ThreeFacesOnOneEdgeIsNonManifold) {
    Mesh m;
    m.name = "fin";
    m.objectPositions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    m.finalize();
    EXPECT_EQ(m.report.nonManifoldEdges, 1u);
    EXPECT_EQ(m.report.openEdges, 6u);
}

TEST(MeshAdjacency, FlippedFaceIsInconsistent) {
    Mesh m = tetrahedron();
    std::swap(m.triangles[3][1], m.triangles[3][2]);
    m.finalize();
    EXPECT_EQ(m.report.inconsistentEdges, 3u);
    EXPECT_FALSE(m.report.closedManifold());
}

TEST(MeshAdjacency, DegenerateFacesAreCountedNotFatal) {
    Mesh m = tetrahedron();
    m.objectPositions.push_back({2, 2, 2});
    m.triangles.push_back({4, 4, 0});         // repeated index
    m.objectPositions.push_back({3, 3, 3});
    m.triangles.push_back({0, 4, 5});         // collinear: zero area
    m.finalize();
    EXPECT_EQ(m.report.degenerateFaces, 2u);
    EXPECT_EQ(m.faceNormals[4], glm::vec3(0.0f));
}

TEST(MeshValidation, NanVertexIsRejectedWithItsIndex) {
    Mesh m = tetrahedron();
    m.objectPositions[2].y = std::numeric_limits<float>::quiet_NaN();
    try {
        m.finalize();
        FAIL() << "NaN vertex accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_SCENE);
        EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
    }
}

TEST(MeshValidation, IndexOutOfRangeIsRejected) {
    Mesh m = tetrahedron();
    m.triangles[1][2] = 99;
    try {
        m.finalize();
        FAIL() << "out-of-range index accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_SCENE);
        EXPECT_NE(std::string(e.what()).find("99"), std::string::npos) << e.what();
    }
}

TEST(MeshReport, JsonNamesEveryCount) {
    Mesh m = tetrahedron();
    m.finalize();
    std::string json = m.report.toJson("my \"tet\"");
    EXPECT_EQ(json,
              "{\"mesh\": \"my \\\"tet\\\"\", \"open_edges\": 0, \"non_manifold_edges\": 0, "
              "\"inconsistent_edges\": 0, \"degenerate_faces\": 0, \"closed_manifold\": true}");
}

TEST(SceneInput, ZeroSizeAreaLightIsRejected) {
    Scene s;
    Light l;
    l.name = "Area";
    l.type = LightType::Disk;
    l.size = 0.0f;
    try {
        s.addLight(l);
        FAIL() << "zero-size light accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_SCENE);
        EXPECT_NE(std::string(e.what()).find("Area"), std::string::npos);
    }
    EXPECT_TRUE(s.lights().empty());
}

TEST(SceneInput, DuplicateLightNamesAreRejected) {
    Scene s;
    Light l;
    l.name = "Key";
    s.addLight(l);
    EXPECT_THROW(s.addLight(l), Error);
}

TEST(SceneInput, RevisionChangesOnEveryEdit) {
    Scene s;
    uint64_t r0 = s.revision();
    s.addMesh(tetrahedron());
    EXPECT_GT(s.revision(), r0);
    EXPECT_NEAR(s.bounds().diagonal(), std::sqrt(3.0f), 1e-6f);
}

TEST(LightGeometry, AreaEqualDiskRadius) {
    Light l;
    l.type = LightType::Rectangle;
    l.size = 2.0f;
    l.sizeY = 1.0f;
    // Area 2 = pi r^2.
    EXPECT_NEAR(l.equivalentRadius(), std::sqrt(2.0f / float(M_PI)), 1e-6f);
    l.type = LightType::Disk;
    EXPECT_NEAR(l.equivalentRadius(), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(l.direction() - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace ss
