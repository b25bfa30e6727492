// Checks the extruded umbra and penumbra volumes: tangent points, trimming, and lateral closure.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "geometry/volumes.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

Mesh box(glm::vec3 lo, glm::vec3 hi) {
    std::vector<glm::vec3> p;
    for (int i = 0; i < 8; ++i) p.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    std::vector<glm::uvec3> t;
    auto quad = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d) { t.push_back({a, b, c}), t.push_back({a, c, d}); };
    quad(0, 2, 3, 1), quad(4, 5, 7, 6), quad(0, 1, 5, 4), quad(2, 6, 7, 3), quad(0, 4, 6, 2), quad(1, 3, 7, 5);
    return test::makeMesh(p, t);
}

Mesh uvSphere(int rings, int segments) {
    Mesh m = test::makeUvSphere({0, 0, 0}, 1.0f, rings, segments, SS_MESH_CAST | SS_MESH_RECEIVE);
    m.name = "test";
    return m;
}

using Key = std::tuple<float, float, float>;
Key key(const glm::vec3& p) { return {p.x, p.y, p.z}; }

// Counts how many triangles use each lateral edge (one end on the mesh, one far end). A volume
// whose side surface is a closed tube uses each exactly twice.
void expectLaterallyClosed(const Mesh& m, const std::vector<VolumeVertex>& soup, const char* what) {
    std::map<Key, int> onMesh;
    for (const glm::vec3& p : m.objectPositions) onMesh[key(p)] = 1;
    std::map<std::pair<Key, Key>, int> uses;
    for (size_t t = 0; t + 2 < soup.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            Key a = key(soup[t + k].position), b = key(soup[t + (k + 1) % 3].position);
            bool na = onMesh.count(a), nb = onMesh.count(b);
            if (na == nb) continue;  // near (silhouette) or far end
            uses[std::minmax(a, b)]++;
        }
    EXPECT_FALSE(uses.empty()) << what;
    for (auto& [e, n] : uses) EXPECT_EQ(n, 2) << what << ": a lateral edge is used " << n << " times";
}

TEST(DbufferVolumes, TangentPointsTouchTheDiskAndSeparateUmbraFromPenumbra) {
    Disk d{{0, 0, 5}, {0, 0, -1}, 1.0f};
    // Edge along y at x = 2, z = 1, tilted in z so its line meets the light plane.
    glm::vec3 v1(2, -1, 1), v2(2, 1, 2);
    EdgeExtrusion x = edgeExtrusion(v1, v2, glm::vec3(-1, 0, 0), d);
    EXPECT_FALSE(x.parallel);
    for (glm::vec3 p : {x.pUmbra, x.pPenumbra}) {
        EXPECT_NEAR(glm::length(p - d.centre), 1.0f, 1e-5f);
        EXPECT_NEAR(p.z, 5.0f, 1e-5f);
        // Tangent: the whole disk lies on one side of the plane through the edge and p.
        glm::vec3 n = glm::cross(v2 - v1, p - v1);
        float lo = 1e9f, hi = -1e9f;
        for (int k = 0; k < 360; ++k) {
            float a = float(k) * float(M_PI) / 180.0f;
            float s = glm::dot(n, d.centre + glm::vec3(std::cos(a), std::sin(a), 0) - v1) / glm::length(n);
            lo = std::min(lo, s), hi = std::max(hi, s);
        }
        EXPECT_GT(lo * hi, -1e-4f) << "plane cuts the disk";
    }
    // Occluder towards -x: the umbra plane touches the far (+x) side of the disk.
    EXPECT_GT(x.pUmbra.x, 0.0f);
    EXPECT_LT(x.pPenumbra.x, 0.0f);
    // Parallel edge: the ends of the diameter across it.
    EdgeExtrusion p = edgeExtrusion({2, -1, 1}, {2, 1, 1}, glm::vec3(-1, 0, 0), d);
    EXPECT_TRUE(p.parallel);
    EXPECT_NEAR(p.pUmbra.x, 1.0f, 1e-6f);
    EXPECT_NEAR(p.pPenumbra.x, -1.0f, 1e-6f);
}

TEST(DbufferVolumes, BoxUnderSmallDiskHasTrimmedClosedUmbraAndFannedPenumbra) {
    Mesh m = box({-1, -1, 0}, {1, 1, 1});
    Disk d{{0.2f, 0.1f, 6}, {0, 0, -1}, 0.5f};
    ShadowVolumes v = extrudeVolumes(m, diskSilhouette(m, d), d, 20.0f);
    EXPECT_EQ(v.umbraQuads, 4u);
    EXPECT_EQ(v.penumbraQuads, 4u);
    EXPECT_EQ(v.trimmedCorners, 4u);
    EXPECT_GT(v.fanTriangles, 0u);
    expectLaterallyClosed(m, v.umbra, "umbra");
    expectLaterallyClosed(m, v.penumbra, "penumbra");
    // Far away the umbra lies inside the hard shadow of the box top seen from the centre and
    // the penumbra outside it: project far vertices from the centre back onto z = 1.
    auto projected = [&](const glm::vec3& p) {
        glm::vec3 q = d.centre + (p - d.centre) * ((d.centre.z - 1.0f) / (d.centre.z - p.z));
        return std::max(std::abs(q.x), std::abs(q.y));
    };
    for (const VolumeVertex& u : v.umbra)
        if (u.position.z < -5) {
            EXPECT_LT(projected(u.position), 1.0f);
        }
    for (const VolumeVertex& u : v.penumbra)
        if (u.position.z < -5) {
            EXPECT_GT(projected(u.position), 1.0f);
        }
}

TEST(DbufferVolumes, SphereUnderWideDiskIsClosedWithSilhouetteFaces) {
    Mesh m = uvSphere(16, 24);
    Disk d{{0.1f, 0, 5}, {0, 0, -1}, 1.5f};
    DiskSilhouette s = diskSilhouette(m, d);
    ShadowVolumes v = extrudeVolumes(m, s, d, 30.0f);
    EXPECT_EQ(v.silhouetteFaces, s.silhouetteFacesCentreBack.size() + s.silhouetteFacesCentreFront.size());
    EXPECT_GT(v.silhouetteFaces, 0u);
    expectLaterallyClosed(m, v.umbra, "umbra");
    expectLaterallyClosed(m, v.penumbra, "penumbra");
    for (const auto* soup : {&v.umbra, &v.penumbra})
        for (const VolumeVertex& x : *soup) {
            EXPECT_TRUE(std::isfinite(x.position.x) && std::isfinite(x.position.y) && std::isfinite(x.position.z));
        }
}

TEST(DbufferVolumes, OpenQuadStaysFiniteAndCountsEdgesThroughTheDisk) {
    // A quad right under the disk centre: its edges' lines are parallel to the light.
    Mesh m = test::makeMesh({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
    Disk d{{0, 0, 3}, {0, 0, -1}, 0.5f};
    ShadowVolumes v = extrudeVolumes(m, diskSilhouette(m, d), d, 10.0f);
    EXPECT_EQ(v.umbraQuads, 4u);
    EXPECT_EQ(v.penumbraQuads, 4u);
    expectLaterallyClosed(m, v.umbra, "umbra");
    expectLaterallyClosed(m, v.penumbra, "penumbra");
    // A vertical fin whose line pierces the disk: not a silhouette of a closed mesh, so the
    // fallback construction must keep everything finite.
    Mesh fin = test::makeMesh({{0, 0, 0}, {0, 0, 1}, {1, 0, 0.5f}}, {{0, 1, 2}});
    ShadowVolumes f = extrudeVolumes(fin, diskSilhouette(fin, d), d, 10.0f);
    EXPECT_GE(f.insideDiskEdges, 1u);
    for (const VolumeVertex& x : f.umbra) EXPECT_TRUE(std::isfinite(x.position.x + x.position.y + x.position.z));
    for (const VolumeVertex& x : f.penumbra) EXPECT_TRUE(std::isfinite(x.position.x + x.position.y + x.position.z));
}

}  // namespace
}  // namespace ss
