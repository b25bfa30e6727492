// Checks that a mirrored mesh (negative-determinant matrix) is the same outward surface as its
// twin given directly in the world, in the mesh data and in every method's shadow.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/mesh.h"
#include "geometry/silhouette.h"
#include "io/metrics.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "test_layers.h"
#include "test_scenes.h"

namespace ss {
namespace {

// An L prism (asymmetric in x and y, so a mirror shows) and a small box beside it, one mesh of
// two closed pieces (dbuffer takes its silhouettes per piece), in object space, outward wound.
Mesh lPrism() {
    const std::vector<glm::vec2> l = {{-0.8f, -0.8f}, {0.8f, -0.8f}, {0.8f, -0.2f},
                                      {-0.2f, -0.2f}, {-0.2f, 0.8f}, {-0.8f, 0.8f}};
    Mesh m = test::makePrism(l, 3, 0.9f, 1.2f, SS_MESH_CAST);
    const Mesh box = test::makeBox({0.3f, 0.3f, 1.3f}, {0.7f, 0.6f, 1.5f}, SS_MESH_CAST);
    const uint32_t base = uint32_t(m.objectPositions.size());
    m.objectPositions.insert(m.objectPositions.end(), box.objectPositions.begin(), box.objectPositions.end());
    for (const glm::uvec3& t : box.triangles) m.triangles.push_back(t + glm::uvec3(base));
    m.name = "L";
    m.finalize();
    return m;
}

struct Mirror {
    std::string name;
    glm::mat4 matrix;
};

// Scale -1 on x (Blender's mirror modifier applied as an object scale), and on x, y and z (a
// point reflection; lifted back above the ground), each shifted a little off the axes.
std::vector<Mirror> mirrors() {
    return {{"x", glm::translate(glm::mat4(1.0f), {0.15f, -0.1f, 0.0f}) * glm::scale(glm::mat4(1.0f), {-1, 1, 1})},
            {"xyz", glm::translate(glm::mat4(1.0f), {0.1f, 0.15f, 2.1f}) * glm::scale(glm::mat4(1.0f), {-1, -1, -1})}};
}

Mesh placed(Mesh m, const glm::mat4& matrix) {
    m.objectToWorld = matrix;
    m.finalize();
    return m;
}

// The same world surface with the identity matrix: vertices mirrored, triangles re-wound so
// they stay counter-clockwise seen from outside.
Mesh twinOf(const Mesh& shape, const glm::mat4& matrix) {
    Mesh m = shape;
    for (glm::vec3& p : m.objectPositions) p = glm::vec3(matrix * glm::vec4(p, 1.0f));
    for (glm::uvec3& t : m.triangles) std::swap(t[1], t[2]);
    m.objectToWorld = glm::mat4(1.0f);
    m.finalize();
    return m;
}

// Each edge's faces and the direction each walks it, by its vertices.
std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<uint32_t, bool>>> edgeWalks(const Mesh& m) {
    std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<uint32_t, bool>>> out;
    for (const Edge& e : m.adjacency.edges)
        for (size_t k = 0; k < e.faces.size(); ++k) out[{e.v0, e.v1}].emplace_back(e.faces[k], e.forward[k]);
    return out;
}

std::vector<std::tuple<uint32_t, uint32_t, uint32_t>> orientedEdges(const std::vector<SilhouetteEdge>& edges) {
    std::vector<std::tuple<uint32_t, uint32_t, uint32_t>> out;
    for (const SilhouetteEdge& e : edges) out.emplace_back(e.a, e.b, e.face);
    std::sort(out.begin(), out.end());
    return out;
}

TEST(MirroredMeshes, WorldNormalsAdjacencyAndSilhouettesAreTheTwins) {
    const Disk disk{{0.3f, 0.2f, 4.0f}, {0.0f, 0.0f, -1.0f}, 0.75f};
    for (const Mirror& mirror : mirrors()) {
        const Mesh mirrored = placed(lPrism(), mirror.matrix);
        const Mesh twin = twinOf(lPrism(), mirror.matrix);
        EXPECT_TRUE(mirrored.mirrored) << mirror.name;
        EXPECT_FALSE(twin.mirrored) << mirror.name;
        ASSERT_EQ(mirrored.faceNormals.size(), twin.faceNormals.size());
        for (size_t f = 0; f < twin.faceNormals.size(); ++f) {
            EXPECT_LT(glm::length(mirrored.faceNormals[f] - twin.faceNormals[f]), 1e-5f) << mirror.name << " face " << f;
            EXPECT_EQ(mirrored.worldTriangle(f), twin.triangles[f]) << mirror.name << " face " << f;
        }
        EXPECT_EQ(edgeWalks(mirrored), edgeWalks(twin)) << mirror.name;
        EXPECT_TRUE(mirrored.report.closedManifold()) << mirror.name;
        const PointSilhouette pm = pointSilhouette(mirrored, disk.centre), pt = pointSilhouette(twin, disk.centre);
        EXPECT_EQ(orientedEdges(pm.edges), orientedEdges(pt.edges)) << mirror.name;
        const DiskSilhouette ds = diskSilhouette(mirrored, disk), dt = diskSilhouette(twin, disk);
        EXPECT_EQ(orientedEdges(ds.umbraEdges), orientedEdges(dt.umbraEdges)) << mirror.name;
        EXPECT_EQ(orientedEdges(ds.penumbraEdges), orientedEdges(dt.penumbraEdges)) << mirror.name;
        EXPECT_FALSE(dt.umbraEdges.empty());
    }
}

TEST(MirroredMeshes, MovingInAndOutOfAMirrorTurnsTheWorldWindingBack) {
    const glm::mat4 mirror = mirrors()[0].matrix;
    Mesh m = placed(lPrism(), glm::mat4(1.0f));
    const Mesh plain = m;
    const Mesh twin = twinOf(lPrism(), mirror);
    m.place(mirror);
    EXPECT_TRUE(m.mirrored);
    EXPECT_EQ(edgeWalks(m), edgeWalks(twin));
    m.place(mirror);  // placed twice the same way: nothing turns again
    EXPECT_EQ(edgeWalks(m), edgeWalks(twin));
    m.place(glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 0.5f}));
    EXPECT_FALSE(m.mirrored);
    EXPECT_EQ(edgeWalks(m), edgeWalks(plain));
    EXPECT_EQ(m.triangles, plain.triangles);  // the shape as given is kept (a saved file round-trips)
    EXPECT_EQ(m.objectPositions, plain.objectPositions);
}

Scene sceneWith(Mesh occluder) {
    Scene s;
    s.addMesh(test::makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(std::move(occluder));
    // Off the axes, so the shadow of the L and of its mirror image differ.
    s.addLight(test::makeDiskLight({0.3f, 0.2f, 4.0f}, 1.5f));
    s.setCamera(test::makeTopCamera(96, 72));
    return s;
}

struct MethodBounds {
    size_t twinPixels;     // pixels where the mirrored mesh and its twin differ by over 1e-3
    double referenceRmse;  // the mirrored mesh against the reference of its twin
};

// The CPU methods see bit-identical world data (the same products, a cross product negated), so
// their renders are the same pixels. The GL ones place the mirrored mesh with its matrix on the
// GPU and the twin as given, which may round a vertex differently: a pixel whose centre lies on
// an edge may change side (measured: none does). rmse against the reference, measured (Release,
// 96 x 72, 256 reference samples; x / xyz), with room for the quick run's 64 samples:
//   reference 0 / 0, sweep 0.014 / 0.012, dbuffer 0.023 / 0.021, pcss and auto (pcss) 0.008 /
//   0.009, occlusion_textures 0.038 / 0.030, penumbra_map 0.063 / 0.048, shadow_map 0.077 / 0.065.
const std::map<std::string, MethodBounds>& bounds() {
    static const std::map<std::string, MethodBounds> b = {
        {"reference", {0, 0.0}},      {"sweep", {0, 0.025}},         {"dbuffer", {4, 0.035}},
        {"auto", {4, 0.035}},         {"penumbra_map", {4, 0.08}},   {"pcss", {4, 0.02}},
        {"shadow_map", {4, 0.10}},    {"occlusion_textures", {4, 0.055}}};
    return b;
}

size_t pixelsApart(const Image& a, const Image& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) n += std::abs(a.pixels[i] - b.pixels[i]) > 1e-3f ? 1 : 0;
    return n;
}

TEST(MirroredMeshes, EveryMethodShadowsAMirroredMeshLikeItsTwin) {
    Renderer renderer(SS_BACKEND_AUTO);
    const int samples = test::quickTests() ? 64 : 256;
    for (const Mirror& mirror : mirrors()) {
        const Scene mirrored = sceneWith(placed(lPrism(), mirror.matrix));
        const Scene twin = sceneWith(twinOf(lPrism(), mirror.matrix));
        const Layers truth = test::run(renderer, twin, "reference", samples);
        for (const auto& [method, bound] : bounds()) {
            const int s = method == "reference" ? samples : 0;
            const Layers a = test::run(renderer, mirrored, method, s);
            const Layers b = test::run(renderer, twin, method, s);
            const Metrics same = compareVisibility(test::layer(a, "V"), test::layer(b, "V"));
            const size_t apart = pixelsApart(test::layer(a, "V"), test::layer(b, "V"));
            EXPECT_LE(apart, bound.twinPixels) << mirror.name << " " << method << ": " << same.toString();
            EXPECT_LE(same.meanAbs, 1e-3) << mirror.name << " " << method << ": " << same.toString();
            const Metrics vsTruth = compareVisibility(test::layer(a, "V"), test::layer(truth, "V"));
            if (method != "reference")
                EXPECT_LE(vsTruth.rmse, bound.referenceRmse) << mirror.name << " " << method << ": " << vsTruth.toString();
            std::printf("%s %-18s twin: %zu pixels apart, %s | reference rmse %.4f\n", mirror.name.c_str(),
                        method.c_str(), apart, same.toString().c_str(), vsTruth.rmse);
        }
    }
}

}  // namespace
}  // namespace ss
