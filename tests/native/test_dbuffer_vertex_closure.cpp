// Are the dbuffer volumes closed at silhouette vertices with three or more silhouette edges?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "geometry/volumes.h"
#include "softshadow/softshadow.h"
#include "test_pcss_support.h"
#include "test_scenes.h"

namespace ss {
namespace {

// A pyramid over a polygon (counter-clockwise in xy at z0) with its apex at `apex`; the base
// is a fan from its centre.
Mesh pyramid(const std::vector<glm::vec2>& base, float z0, const glm::vec3& apex) {
    std::vector<glm::vec3> p;
    for (glm::vec2 b : base) p.push_back({b.x, b.y, z0});
    uint32_t n = uint32_t(base.size()), top = n, bottom = n + 1;
    p.push_back(apex);
    p.push_back({apex.x, apex.y, z0});
    std::vector<glm::uvec3> t;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t j = (i + 1) % n;
        t.push_back({i, j, top});
        t.push_back({j, i, bottom});
    }
    return test::makeMesh(p, t);
}

// A prism over a star-shaped polygon, caps as fans from the centre.
Mesh prism(const std::vector<glm::vec2>& base, float z0, float z1) {
    std::vector<glm::vec3> p;
    uint32_t n = uint32_t(base.size());
    for (glm::vec2 b : base) p.push_back({b.x, b.y, z0});
    for (glm::vec2 b : base) p.push_back({b.x, b.y, z1});
    p.push_back({0, 0, z0});
    p.push_back({0, 0, z1});
    std::vector<glm::uvec3> t;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t j = (i + 1) % n;
        t.push_back({i, j, n + j});
        t.push_back({i, n + j, n + i});
        t.push_back({j, i, 2 * n});
        t.push_back({n + i, n + j, 2 * n + 1});
    }
    return test::makeMesh(p, t);
}

std::vector<glm::vec2> circle(int n, float r) {
    std::vector<glm::vec2> out;
    for (int i = 0; i < n; ++i) {
        float a = 2.0f * float(M_PI) * float(i) / float(n);
        out.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return out;
}

std::vector<glm::vec2> star(int points, float outer, float inner) {
    std::vector<glm::vec2> out;
    for (int i = 0; i < 2 * points; ++i) {
        float a = float(M_PI) * float(i) / float(points);
        float r = i % 2 ? inner : outer;
        out.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return out;
}

Mesh octahedron(float rx, float ry, float rz, float z0) {
    return test::makeMesh({{rx, 0, z0}, {0, ry, z0}, {-rx, 0, z0}, {0, -ry, z0}, {0, 0, z0 + rz}, {0, 0, z0 - rz}},
                         {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}, {1, 0, 5}, {2, 1, 5}, {3, 2, 5}, {0, 3, 5}});
}

size_t maxEdges(const std::vector<SilhouetteVertex>& vs) {
    size_t m = 0;
    for (const auto& v : vs) m = std::max(m, v.edges.size());
    return m;
}

// Two octahedra touching at one vertex (a's top is b's bottom): a non-manifold vertex. With
// `split` b's bottom is a vertex of its own at the same place: two 2-edge silhouette vertices.
Mesh twoOctahedra(bool split = false) {
    Mesh a = octahedron(0.5f, 0.5f, 0.5f, 1.0f), b = octahedron(0.5f, 0.5f, 0.5f, 2.0f);
    std::vector<glm::vec3> p = a.objectPositions;
    std::vector<glm::uvec3> t = a.triangles;
    for (int k = 0; k < 5; ++k) p.push_back(b.objectPositions[k]);
    if (split) p.push_back(a.objectPositions[4]);
    for (glm::uvec3 tri : b.triangles) {
        glm::uvec3 m;
        for (int k = 0; k < 3; ++k) m[k] = tri[k] == 5 ? (split ? 11 : 4) : tri[k] + 6;
        t.push_back(m);
    }
    return test::makeMesh(p, t);
}

using Key = std::tuple<float, float, float>;
Key key(const glm::vec3& p) { return {p.x, p.y, p.z}; }

// Watertightness of a volume's side surface: every edge with one end on the mesh and one far
// end (the quads' and fans' lateral edges) must be used by exactly two triangles; the volume's
// near end is the occluder and its far end lies beyond every receiver. Returns the edges used
// once (a crack) or three times and more.
size_t badLateralEdges(const Mesh& m, const std::vector<VolumeVertex>& soup) {
    std::map<Key, int> onMesh;
    for (const glm::vec3& p : m.objectPositions) onMesh[key(p)] = 1;
    std::map<std::pair<Key, Key>, int> uses;
    for (size_t t = 0; t + 2 < soup.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            Key a = key(soup[t + k].position), b = key(soup[t + (k + 1) % 3].position);
            if (onMesh.count(a) == onMesh.count(b)) continue;
            uses[std::minmax(a, b)]++;
        }
    size_t bad = 0;
    for (auto& [e, n] : uses) bad += n != 2;
    return uses.empty() && !soup.empty() ? 1 : bad;
}

struct Case {
    const char* name;
    Mesh mesh;
    Disk disk;
};

// Configurations found by a random search over disk positions, tilts and sizes; each has a
// vertex with 3+ edges of the umbra or penumbra silhouette (asserted below). A right cone and a
// regular octahedron need a large, tilted or close light for that (their face normals at a
// vertex lie on one circle); a star-based pyramid's apex has 4-6 under an ordinary light. A
// prism never has one (three planes meet at each vertex: at most two changes of class around it).
std::vector<Case> cases() {
    auto disk = [](glm::vec3 c, glm::vec3 n, float r) { return Disk{c, glm::normalize(n), r}; };
    std::vector<Case> out;
    out.push_back({"cone, 4 penumbra edges at the apex", pyramid(circle(24, 0.6f), 0.5f, {0, 0, 1.6f}),
                   disk({0.76f, 0.54f, 3.49f}, {-0.200f, 0.958f, -0.206f}, 1.85f)});
    out.push_back({"cone, 4 umbra edges", pyramid(circle(24, 0.6f), 0.5f, {0, 0, 1.6f}),
                   disk({-0.69f, 1.92f, -0.25f}, {-0.669f, -0.609f, -0.426f}, 2.57f)});
    out.push_back({"octahedron, 4 umbra edges", octahedron(0.7f, 0.7f, 0.7f, 1.0f),
                   disk({-0.37f, -0.50f, 3.36f}, {-0.314f, -0.572f, -0.758f}, 2.18f)});
    out.push_back({"octahedron, 4 penumbra edges", octahedron(0.7f, 0.7f, 0.7f, 1.0f),
                   disk({2.96f, 0.0f, 0.98f}, {0.016f, -0.591f, -0.807f}, 1.71f)});
    out.push_back({"star pyramid, 6 edges at the apex", pyramid(star(5, 0.8f, 0.3f), 0.5f, {0, 0, 1.6f}),
                   disk({0.85f, -1.02f, 2.74f}, {0, 0, -1}, 0.43f)});
    out.push_back({"two octahedra touching", twoOctahedra(), disk({-3.0f, 0.0f, 2.2f}, {0, 0, -1}, 0.75f)});
    return out;
}


TEST(DbufferVertexClosure, VolumesAreWatertightAtVerticesWithThreeOrMoreSilhouetteEdges) {
    for (const Case& c : cases()) {
        DiskSilhouette s = diskSilhouette(c.mesh, c.disk);
        size_t mu = maxEdges(s.umbraVertices), mp = maxEdges(s.penumbraVertices);
        ASSERT_GE(std::max(mu, mp), 3u) << c.name << ": the case no longer has such a vertex";
        ShadowVolumes v = extrudeVolumes(c.mesh, s, c.disk, 20.0f);
        size_t bu = badLateralEdges(c.mesh, v.umbra), bp = badLateralEdges(c.mesh, v.penumbra);
        std::printf("[dbuffer] %s: umbra %zu / penumbra %zu edges at a vertex; %zu corners there; %zu + %zu open "
                    "lateral edges\n", c.name, mu, mp, v.multiEdgeCorners, bu, bp);
        EXPECT_GT(v.multiEdgeCorners, 0u) << c.name;
        EXPECT_EQ(v.openCornerEnds, 0u) << c.name;
        EXPECT_EQ(bu, 0u) << c.name << ": umbra volume";
        EXPECT_EQ(bp, 0u) << c.name << ": penumbra volume";
    }
}

TEST(DbufferVertexClosure, StarPrismVolumesAreWatertight) {
    Mesh m = prism(star(5, 0.8f, 0.3f), 0.5f, 1.0f);
    for (Disk d : {Disk{{0.85f, -1.02f, 2.74f}, {0, 0, -1}, 0.43f}, Disk{{0.2f, 0.1f, 4.0f}, {0, 0, -1}, 1.5f}}) {
        DiskSilhouette s = diskSilhouette(m, d);
        EXPECT_EQ(maxEdges(s.umbraVertices), 2u);
        ShadowVolumes v = extrudeVolumes(m, s, d, 20.0f);
        EXPECT_EQ(badLateralEdges(m, v.umbra), 0u);
        EXPECT_EQ(badLateralEdges(m, v.penumbra), 0u);
    }
}

// The shadow of the star pyramid (apex with 4-6 silhouette edges) and of the two touching
// octahedra against the reference: no light leaking into the reference's umbra, no dark
// crack in its lit region, and the error of the shared scenes.
TEST(DbufferVertexClosure, NoLeakInTheShadowAtMultiEdgeVertices) {
    struct Shadow {
        const char* name;
        Mesh mesh;
        glm::vec3 light;
        float diameter;
    };
    std::vector<Shadow> scenes;
    scenes.push_back({"star pyramid", pyramid(star(5, 2.0f, 0.8f), 0.3f, {0, 0, 1.4f}), {0.85f, -1.02f, 4.0f}, 0.6f});
    scenes.push_back({"two octahedra", twoOctahedra(), {-3.0f, 0.0f, 2.2f}, 1.5f});
    for (Shadow& sc : scenes) {
        Scene scene;
        scene.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
        sc.mesh.flags = SS_MESH_CAST;
        scene.addMesh(sc.mesh);
        scene.addLight(test::makeDiskLight(sc.light, sc.diameter));
        scene.setCamera(test::makeTopCamera());
        DiskSilhouette s = diskSilhouette(sc.mesh, Disk{sc.light, {0, 0, -1}, 0.5f * sc.diameter});
        ASSERT_GE(std::max(maxEdges(s.umbraVertices), maxEdges(s.penumbraVertices)), 3u) << sc.name;
        Layers ref = test::renderReference(scene);
        Layers dbuf = test::renderWith(scene, "dbuffer", {{"debug.raw_layers", "true"}});
        const Image& V = *dbuf.find("V");
        const Image& R = *ref.find("V");
        const Image& mask = *ref.find("mask");
        size_t leaks = 0, cracks = 0, umbra = 0, lit = 0;
        for (size_t i = 0; i < V.pixels.size(); ++i) {
            if (!(mask.pixels[i] > 0.5f)) continue;
            if (R.pixels[i] < 0.02f) ++umbra, leaks += V.pixels[i] > 0.5f;
            if (R.pixels[i] > 0.98f) ++lit, cracks += V.pixels[i] < 0.5f;
        }
        Metrics m = test::compareToReference(dbuf, ref);
        std::printf("[dbuffer] %s: %zu leaks in %zu umbra px, %zu cracks in %zu lit px; %s\n", sc.name, leaks, umbra,
                    cracks, lit, m.toString().c_str());
        EXPECT_GT(umbra, 50u) << sc.name;
        EXPECT_EQ(leaks, 0u) << sc.name;
        EXPECT_EQ(cracks, 0u) << sc.name;
        EXPECT_LT(m.rmse, 0.045) << sc.name;
    }
    // Where two loops of the silhouette touch, each gets exactly the corner it would get alone:
    // the touching octahedra render as the same two with the shared vertex split in two.
    auto render = [](Mesh mesh) {
        Scene scene;
        scene.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
        mesh.flags = SS_MESH_CAST;
        scene.addMesh(mesh);
        scene.addLight(test::makeDiskLight({-3.0f, 0.0f, 2.2f}, 1.5f));
        scene.setCamera(test::makeTopCamera());
        return test::renderWith(scene, "dbuffer");
    };
    Metrics same = compareVisibility(*render(twoOctahedra()).find("V"), *render(twoOctahedra(true)).find("V"));
    EXPECT_LT(same.maxAbs, 1e-5) << same.toString();
}

}  // namespace
}  // namespace ss
