// How the CAD-like assembly test scene is built in code (parts, open shells, split faces).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "test_assembly_scene.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "io/primitives.h"
#include "softshadow/softshadow.h"

namespace ss::test {

namespace {

// Rigid placements only: the winding stays outward.
void place(TriangleSoup& s, const glm::mat4& m) {
    for (glm::vec3& p : s.positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
}

TriangleSoup boxSoup(const glm::vec3& lo, const glm::vec3& hi) {
    TriangleSoup s = ss::makeBox(hi - lo, 1);
    place(s, glm::translate(glm::mat4(1.0f), 0.5f * (lo + hi)));
    return s;
}

// A cylinder from `a` to `b`; `caps` false leaves an open tube.
TriangleSoup cylinderSoup(const glm::vec3& a, const glm::vec3& b, float radius, int segments,
                          bool caps = true) {
    const glm::vec3 axis = b - a;
    TriangleSoup s = ss::makeCylinder(radius, glm::length(axis), segments);
    if (!caps) {
        // makeCylinder's last two vertices are the caps' centres.
        const uint32_t centres = uint32_t(s.positions.size()) - 2;
        std::vector<glm::uvec3> side;
        for (const glm::uvec3& t : s.triangles)
            if (t[0] < centres && t[1] < centres && t[2] < centres) side.push_back(t);
        s.triangles = std::move(side);
        s.positions.resize(centres);
    }
    const glm::vec3 z(0.0f, 0.0f, 1.0f), dir = glm::normalize(axis);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), 0.5f * (a + b));
    const glm::vec3 turn = glm::cross(z, dir);
    if (glm::length(turn) > 1e-6f) m = glm::rotate(m, std::acos(glm::dot(z, dir)), glm::normalize(turn));
    place(s, m);
    return s;
}

// The box without the faces whose outward normal is +Z (a tray open at the top).
TriangleSoup traySoup(const glm::vec3& lo, const glm::vec3& hi) {
    TriangleSoup s = boxSoup(lo, hi);
    std::vector<glm::uvec3> kept;
    for (const glm::uvec3& t : s.triangles) {
        glm::vec3 n =
            glm::cross(s.positions[t[1]] - s.positions[t[0]], s.positions[t[2]] - s.positions[t[0]]);
        if (!(n.z > 0.0f && std::abs(n.x) < 1e-6f && std::abs(n.y) < 1e-6f)) kept.push_back(t);
    }
    s.triangles = std::move(kept);
    return s;
}

// A sheet-metal U channel modelled as one surface (no thickness): floor at z0, walls to z1,
// along x, open at both ends and along the top.
TriangleSoup channelSoup(float x0, float x1, float y0, float y1, float z0, float z1) {
    TriangleSoup s;
    s.positions = {{x0, y0, z1}, {x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1},
                   {x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}};
    auto quad = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
        s.triangles.push_back({a, b, c});
        s.triangles.push_back({a, c, d});
    };
    quad(0, 1, 5, 4);  // wall at y0
    quad(1, 2, 6, 5);  // floor
    quad(2, 3, 7, 6);  // wall at y1
    return s;
}

// A horizontal rectangle facing up: a sheet with only open edges.
TriangleSoup sheetSoup(float x0, float x1, float y0, float y1, float z) {
    TriangleSoup s;
    s.positions = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
    s.triangles = {{0, 1, 2}, {0, 2, 3}};
    return s;
}

// Gives each vertex one copy per group of its faces whose normals lie within 30 degrees of the
// group's first face: flat faces of a box become separate patches, a cylinder's side stays one.
TriangleSoup splitAtHardEdges(const TriangleSoup& in) {
    const float cosLimit = std::cos(glm::radians(30.0f));
    std::vector<glm::vec3> normals;
    for (const glm::uvec3& t : in.triangles)
        normals.push_back(glm::normalize(
            glm::cross(in.positions[t[1]] - in.positions[t[0]], in.positions[t[2]] - in.positions[t[0]])));
    // Per vertex: the first normal of each group and the new vertex it maps to.
    std::vector<std::vector<std::pair<glm::vec3, uint32_t>>> groups(in.positions.size());
    TriangleSoup out;
    for (size_t f = 0; f < in.triangles.size(); ++f) {
        glm::uvec3 t;
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = in.triangles[f][k];
            uint32_t id = 0xffffffffu;
            for (const auto& [n, copy] : groups[v])
                if (glm::dot(n, normals[f]) > cosLimit) id = copy;
            if (id == 0xffffffffu) {
                id = uint32_t(out.positions.size());
                out.positions.push_back(in.positions[v]);
                groups[v].emplace_back(normals[f], id);
            }
            t[k] = id;
        }
        out.triangles.push_back(t);
    }
    return out;
}

std::vector<std::pair<std::string, TriangleSoup>> parts(int fine) {
    std::vector<std::pair<std::string, TriangleSoup>> p;
    auto add = [&](const std::string& name, TriangleSoup s) { p.emplace_back(name, std::move(s)); };
    add("base", boxSoup({-1.0f, -0.7f, 0.60f}, {1.0f, 0.7f, 0.68f}));
    // Walls standing on the base: their bottom faces lie in the base's top face.
    add("wall_left", boxSoup({-1.0f, -0.7f, 0.68f}, {-0.92f, 0.7f, 1.20f}));
    add("wall_right", boxSoup({0.92f, -0.7f, 0.68f}, {1.0f, 0.7f, 1.20f}));
    // A shaft through both walls, discs and nuts on it.
    add("shaft", cylinderSoup({-1.1f, 0.35f, 0.98f}, {1.1f, 0.35f, 0.98f}, 0.07f, 24 * fine));
    for (int i = 0; i < 5; ++i) {
        float x = -0.6f + 0.3f * float(i);
        add("disc" + std::to_string(i),
            cylinderSoup({x - 0.02f, 0.35f, 0.98f}, {x + 0.02f, 0.35f, 0.98f}, 0.22f, 32 * fine));
    }
    for (float x : {-1.06f, -0.86f, 0.86f, 1.06f})
        add("nut", cylinderSoup({x - 0.02f, 0.35f, 0.98f}, {x + 0.02f, 0.35f, 0.98f}, 0.11f, 6));
    // A row of thin fins standing on the base.
    for (int i = 0; i < 12; ++i) {
        float x = -0.8f + 0.07f * float(i);
        add("fin" + std::to_string(i), boxSoup({x, -0.6f, 0.68f}, {x + 0.02f, -0.1f, 0.95f}));
    }
    // Stacked blocks: each one's bottom face lies inside the top face of the one below.
    add("block0", boxSoup({0.2f, -0.6f, 0.68f}, {0.6f, -0.3f, 0.78f}));
    add("block1", boxSoup({0.25f, -0.58f, 0.78f}, {0.55f, -0.32f, 0.88f}));
    add("block2", boxSoup({0.3f, -0.55f, 0.88f}, {0.5f, -0.35f, 0.98f}));
    // A cover resting on the left wall, bolts sunk into it, ribs hanging below it through it.
    add("cover", boxSoup({-1.0f, 0.05f, 1.20f}, {0.3f, 0.7f, 1.25f}));
    for (int i = 0; i < 8; ++i) {
        float x = -0.85f + 0.15f * float(i % 4) + (i < 4 ? 0.0f : 0.5f), y = i < 4 ? 0.15f : 0.6f;
        add("bolt" + std::to_string(i), cylinderSoup({x, y, 1.18f}, {x, y, 1.30f}, 0.035f, 16 * fine));
    }
    for (int i = 0; i < 6; ++i) {
        float x = -0.9f + 0.2f * float(i);
        add("rib" + std::to_string(i), boxSoup({x, 0.1f, 1.10f}, {x + 0.05f, 0.65f, 1.22f}));
    }
    // L brackets: two interpenetrating boxes each.
    for (int i = 0; i < 3; ++i) {
        float y = -0.6f + 0.25f * float(i);
        add("bracket_foot" + std::to_string(i), boxSoup({0.65f, y, 0.68f}, {0.85f, y + 0.15f, 0.72f}));
        add("bracket_arm" + std::to_string(i), boxSoup({0.65f, y, 0.70f}, {0.69f, y + 0.15f, 0.95f}));
    }
    // Open shells: tubes without caps, a tray without a lid, a sheet-metal channel on a post.
    add("tube0", cylinderSoup({0.55f, 0.0f, 0.68f}, {0.55f, 0.0f, 1.10f}, 0.12f, 24 * fine, false));
    add("tube1", cylinderSoup({-0.5f, 0.0f, 0.68f}, {-0.5f, 0.0f, 1.05f}, 0.08f, 24 * fine, false));
    add("tray", traySoup({0.05f, -0.25f, 0.68f}, {0.4f, -0.05f, 0.80f}));
    add("post", cylinderSoup({0.85f, 0.05f, 0.68f}, {0.85f, 0.05f, 1.35f}, 0.04f, 16 * fine));
    add("channel", channelSoup(0.4f, 0.9f, -0.2f, 0.3f, 1.35f, 1.45f));
    // Feet under the base (their tops touch its bottom face).
    for (float x : {-0.9f, 0.9f})
        for (float y : {-0.6f, 0.6f}) add("foot", cylinderSoup({x, y, 0.5f}, {x, y, 0.6f}, 0.06f, 16 * fine));
    // Thin rods across the top and guard sheets with no thickness.
    for (int i = 0; i < 5; ++i) {
        float x = -0.8f + 0.2f * float(i);
        add("rod" + std::to_string(i), cylinderSoup({x, -0.75f, 1.32f}, {x, 0.75f, 1.32f}, 0.02f, 12 * fine));
    }
    add("guard0", sheetSoup(-0.9f, -0.5f, -0.65f, -0.3f, 1.40f));
    add("guard1", sheetSoup(-0.4f, -0.1f, -0.65f, -0.35f, 1.40f));
    add("guard2", sheetSoup(0.05f, 0.35f, -0.7f, -0.45f, 1.15f));
    add("guard3", sheetSoup(-0.3f, 0.2f, 0.0f, 0.04f, 1.02f));
    return p;
}

Mesh meshOf(const std::string& name, const TriangleSoup& s, uint32_t flags) {
    Mesh m;
    m.name = name;
    m.objectPositions = s.positions;
    m.triangles = s.triangles;
    m.flags = flags;
    m.finalize();
    return m;
}

}  // namespace

size_t assemblyParts() { return parts(1).size(); }

Scene sceneAssembly(const AssemblyParams& p) {
    Scene s;
    s.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addLight(makeDiskLight({p.scene.lightShift.x, p.scene.lightShift.y, p.scene.lightHeight},
                             p.scene.lightDiameter));
    Camera camera = makeTopCamera(p.scene.width, p.scene.height);
    if (p.scene.cameraZoom != 1.0f)
        camera = makeLookAtCamera({0.0f, -2.5f, 8.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                  2.0f * std::atan(std::tan(glm::radians(22.5f)) / p.scene.cameraZoom),
                                  p.scene.width, p.scene.height, 0.1f, 50.0f);
    s.setCamera(camera);
    TriangleSoup all;
    int n = 0;
    for (auto& [name, soup] : parts(p.tessellation)) {
        for (glm::vec3& v : soup.positions) v.z += p.scene.occluderLift;
        TriangleSoup part = p.splitHardEdges ? splitAtHardEdges(soup) : soup;
        if (!p.oneMesh) {
            s.addMesh(meshOf(name + "_" + std::to_string(n++), part, SS_MESH_CAST));
            continue;
        }
        const uint32_t base = uint32_t(all.positions.size());
        all.positions.insert(all.positions.end(), part.positions.begin(), part.positions.end());
        for (const glm::uvec3& t : part.triangles) all.triangles.push_back(t + glm::uvec3(base));
    }
    if (p.oneMesh) s.addMesh(meshOf("assembly", all, SS_MESH_CAST));
    return s;
}

}  // namespace ss::test
