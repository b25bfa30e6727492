// Checks dbuffer and penumbra_map against the reference on a CAD-like assembly of many parts:
// separate, touching and interpenetrating closed parts and open shells, as separate meshes, as
// one mesh, and with every hard edge split (a flat-shaded export).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scene_cache/scene_cache.h"
#include "methods/penumbra_map.h"
#include "test_assembly_scene.h"
#include "test_pcss_support.h"

namespace ss::test {
namespace {

// The assembly as the soft-shadow tests view it: the light moved sideways so the shadow falls
// beside the assembly, the camera zoomed in on both.
AssemblyParams viewed(bool oneMesh = false, bool split = false) {
    AssemblyParams p;
    p.scene = softSceneParams();
    p.scene.cameraZoom = 1.2f;
    p.scene.width = 200, p.scene.height = 150;
    p.oneMesh = oneMesh;
    p.splitHardEdges = split;
    return p;
}

struct Measured {
    Metrics method, shadowMap;
};

Measured measure(const Scene& scene, const Layers& ref, const std::string& method, const std::string& name) {
    Layers l = renderWith(scene, method);
    Layers sm = renderWith(scene, "shadow_map");
    Measured m{compareToReference(l, ref), compareToReference(sm, ref)};
    std::printf("[many parts] %s %s: %s\n[many parts] %s shadow_map: %s\n", name.c_str(), method.c_str(),
                m.method.toString().c_str(), name.c_str(), m.shadowMap.toString().c_str());
    dumpPng("assembly_" + name + "_" + method, *l.find("V"));
    return m;
}

// The assembly's umbra is where the ray stays inside some part's umbra volume and its penumbra
// is the darkest part's. Measured (200 x 150, 256 reference samples): RMSE 0.047, umbra IoU
// 0.73, lit IoU 0.991 (shadow_map 0.100 / 0.50 / 0.94; pcss 0.025 / 0.80 / 0.987). Before:
// the umbra read as penumbra (one nearest exit over all parts: the first part's own, centimetres
// behind it) and the outer penumbra as lit (the farthest penumbra entry of all parts): RMSE
// 0.101, umbra IoU 0.05, lit IoU 0.942.
TEST(ManyParts, DbufferHoldsTheAssemblysUmbraAndPenumbra) {
    Scene scene = sceneAssembly(viewed());
    ASSERT_EQ(scene.meshes().size(), assemblyParts() + 1);
    Layers ref = renderReference(scene);
    dumpPng("assembly_reference", *ref.find("V"));
    Measured m = measure(scene, ref, "dbuffer", "parts");
    EXPECT_LT(m.method.rmse, 0.06);
    EXPECT_GT(m.method.umbraIoU, 0.6);
    EXPECT_GT(m.method.litIoU, 0.98);
    EXPECT_LT(m.method.rmse, m.shadowMap.rmse - 0.03);
}

// One mesh holding every part (a CAD file imported as one object) and parts whose faces are
// split at every hard edge (each face of a box an open patch) render as the separate closed
// parts do. Before: umbra IoU 0.05 (one mesh) and 0.013 (split: every patch border an open
// silhouette edge).
TEST(ManyParts, DbufferRendersOneMeshAndSplitFacesAsSeparateParts) {
    Scene parts = sceneAssembly(viewed());
    Layers ref = renderReference(parts);
    Metrics base = compareToReference(renderWith(parts, "dbuffer"), ref);
    for (const auto& [oneMesh, split] : {std::pair{true, false}, {false, true}, {true, true}}) {
        Scene scene = sceneAssembly(viewed(oneMesh, split));
        const std::string name = std::string(oneMesh ? "one_mesh" : "parts") + (split ? "_split" : "");
        Measured m = measure(scene, ref, "dbuffer", name);
        EXPECT_NEAR(m.method.rmse, base.rmse, 0.003) << name;
        EXPECT_NEAR(m.method.umbraIoU, base.umbraIoU, 0.02) << name;
        EXPECT_GT(m.method.umbraIoU, 0.6) << name;
    }
}

// penumbra_map on the assembly: its outer penumbra is right (lit IoU above shadow_map's), its
// umbra is the hard shadow (the paper's limit: penumbra_map.md). Measured: RMSE 0.083, lit IoU
// 0.982 against shadow_map's 0.100 / 0.940.
TEST(ManyParts, PenumbraMapOnTheAssemblyBeatsTheHardShadow) {
    Scene scene = sceneAssembly(viewed());
    Layers ref = renderReference(scene);
    Measured m = measure(scene, ref, "penumbra_map", "parts");
    EXPECT_LT(m.method.rmse, m.shadowMap.rmse - 0.01);
    EXPECT_GT(m.method.litIoU, m.shadowMap.litIoU + 0.02);
    EXPECT_NEAR(m.method.umbraIoU, m.shadowMap.umbraIoU, 0.02);
}

// A finely tessellated silhouette turns by a few degrees per vertex: each cone is only its
// corner's sector, not a whole circle of the cone's radius. Pass 2's fill then follows the
// silhouette's length, not its vertex count (bench: BM_PenumbraMapAssembly). Measured on the
// assembly with cylinders of 96 to 256 segments: the cones cover 0.094 of the area whole cones
// would, 56 of the 4685 cones stay whole (where the two edges fold back on each other, or a
// sheet has no tangent to its cones); every cone was whole before (1.0).
TEST(ManyParts, PenumbraMapConesAreSectorsOnAFineSilhouette) {
    AssemblyParams p = viewed();
    p.tessellation = 8;
    Scene scene = sceneAssembly(p);
    const Light& light = scene.lights()[0];
    ShadowMap map = fitShadowMap(light, scene.bounds(), 1024);
    ConesSheets g = buildPenumbraGeometry(scene, 0, map, penumbraMapLightRadius(light), {});
    ASSERT_GT(g.cones(), 1000u);
    // Cones and sheets are appended mesh by mesh: a cone's triangles run to the next cone or sheet.
    std::vector<uint32_t> starts(g.coneFirstTriangle.begin(), g.coneFirstTriangle.end());
    starts.insert(starts.end(), g.sheetFirstTriangle.begin(), g.sheetFirstTriangle.end());
    starts.push_back(uint32_t(g.triangles.size()));
    std::sort(starts.begin(), starts.end());
    // Areas on the far plane (where every cone's base lies), against whole circles of the
    // cones' radii.
    const glm::vec3 axis = map.axis;
    double coneArea = 0.0, wholeArea = 0.0;
    size_t whole = 0;
    for (uint32_t c : g.coneFirstTriangle) {
        const uint32_t end = *std::upper_bound(starts.begin(), starts.end(), c);
        const glm::uvec3& first = g.triangles[c];
        const float zv = g.vertices[first[0]].zv;
        const float r = coneRadius(
            PenumbraLight{map.origin, axis, penumbraMapLightRadius(light), map.nearPlane, map.farPlane}, zv);
        wholeArea += M_PI * double(r) * double(r);
        whole += end - c >= 16;
        for (uint32_t t = c; t < end; ++t) {
            const glm::vec3 a = g.vertices[g.triangles[t][1]].position,
                            b = g.vertices[g.triangles[t][2]].position;
            const glm::vec3 tip = g.vertices[g.triangles[t][0]].position;
            const glm::vec3 base =
                map.origin + (tip - map.origin) * (map.farPlane / glm::dot(tip - map.origin, axis));
            coneArea += 0.5 * double(glm::length(glm::cross(a - base, b - base)));
        }
    }
    const double share = coneArea / wholeArea;
    std::printf(
        "[many parts] penumbra_map: %zu cones (%zu whole), %zu sheets; cone area %.3f of whole cones\n",
        g.cones(), whole, g.sheets(), share);
    EXPECT_LT(share, 0.2);
}

// A binary STL file's triangles as shipped: every triangle with its own three vertices (STL has
// no shared vertices, like a CAD export); empty when the file is missing or not binary STL.
Mesh readBinaryStl(const std::string& path, const glm::mat4& placed) {
    Mesh m;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return m;
    unsigned char header[84];
    uint32_t count = 0;
    if (std::fread(header, 1, 84, f) == 84) std::memcpy(&count, header + 80, 4);
    for (uint32_t i = 0; i < count; ++i) {
        unsigned char record[50];
        if (std::fread(record, 1, 50, f) != 50) {
            m.triangles.clear();
            break;
        }
        float v[9];
        std::memcpy(v, record + 12, sizeof v);
        const uint32_t base = uint32_t(m.objectPositions.size());
        for (int k = 0; k < 3; ++k)
            m.objectPositions.push_back(glm::vec3(placed * glm::vec4(v[3 * k], v[3 * k + 1], v[3 * k + 2], 1.0f)));
        m.triangles.push_back({base, base + 1, base + 2});
    }
    std::fclose(f);
    if (m.triangles.empty()) return Mesh{};
    m.name = "stl";
    m.flags = SS_MESH_CAST;
    m.finalize();
    return m;
}

// A real CAD export from a Debian package (openscad-testing-data, `make deps`): a circuit board
// with its components, 900 triangles as an STL soup (no vertex shared; welded it is one closed
// manifold), scaled to 1.5 m x 2.8 m and held 1.2 m over the ground under the shared disk.
// Measured (200 x 150): dbuffer RMSE 0.094, umbra IoU 0.30, lit IoU 0.988; before 0.175 / 0.00 /
// 0.919 (every triangle an open patch, each of its edges a silhouette: worse than shadow_map,
// 0.120 / 0.54 / 0.914). What is left is light streaks inside the board's umbra, fanning out
// from its drill holes: one concave part, one surface per D-buffer texel (dbuffer.md, "Many
// parts"). penumbra_map: 0.101, unchanged.
TEST(ManyParts, DbufferOnARealCadExport) {
    const std::string path = "/usr/share/openscad/testdata/stl/adns2610_dev_circuit_inv.stl";
    glm::mat4 placed = glm::translate(glm::mat4(1.0f), glm::vec3(-0.75f, -1.4f, 1.2f)) *
                       glm::scale(glm::mat4(1.0f), glm::vec3(0.1f)) *
                       glm::translate(glm::mat4(1.0f), glm::vec3(5.0f, 7.0f, 0.0f));
    Mesh board = readBinaryStl(path, placed);
    if (board.triangles.empty())
        GTEST_SKIP() << path << " is missing (Debian package openscad-testing-data, `make deps`)";
    ASSERT_EQ(board.triangles.size(), 900u);
    EXPECT_GT(board.report.openEdges, 0u);
    Scene scene = sceneAssembly(viewed());
    Scene s;
    s.addMesh(scene.meshes()[0]);
    s.addMesh(std::move(board));
    s.addLight(scene.lights()[0]);
    s.setCamera(scene.camera());
    Layers ref = renderReference(s);
    dumpPng("stl_reference", *ref.find("V"));
    Measured m = measure(s, ref, "dbuffer", "stl");
    Measured pm = measure(s, ref, "penumbra_map", "stl");
    EXPECT_LT(m.method.rmse, 0.11);
    EXPECT_GT(m.method.umbraIoU, 0.2);
    EXPECT_GT(m.method.litIoU, 0.98);
    EXPECT_LT(m.method.rmse, m.shadowMap.rmse - 0.01);
    EXPECT_LT(pm.method.rmse, pm.shadowMap.rmse);
}

}  // namespace
}  // namespace ss::test
