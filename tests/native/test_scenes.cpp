// How the shared quality-test scenes are built in code (box, L, overlapping boxes, torus).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "test_scenes.h"

#include <cmath>
#include <cstdlib>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "io/primitives.h"
#include "softshadow/softshadow.h"

namespace ss::test {

Mesh makePrism(const std::vector<glm::vec2>& polygon, size_t fanVertex, float z0, float z1,
               uint32_t flags) {
    Mesh m;
    m.name = "prism";
    const uint32_t n = uint32_t(polygon.size());
    for (const glm::vec2& p : polygon) m.objectPositions.push_back({p.x, p.y, z0});
    for (const glm::vec2& p : polygon) m.objectPositions.push_back({p.x, p.y, z1});
    const uint32_t f = uint32_t(fanVertex);
    for (uint32_t k = 1; k + 1 < n; ++k) {
        uint32_t a = (f + k) % n, b = (f + k + 1) % n;
        m.triangles.push_back({n + f, n + a, n + b});  // top: counter-clockwise from above
        m.triangles.push_back({f, b, a});              // bottom: faces down
    }
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t j = (i + 1) % n;
        // The right of a counter-clockwise edge is outside.
        m.triangles.push_back({i, j, n + j});
        m.triangles.push_back({i, n + j, n + i});
    }
    m.flags = flags;
    m.finalize();
    return m;
}

Mesh makeBox(const glm::vec3& lo, const glm::vec3& hi, uint32_t flags) {
    Mesh m = makePrism({{lo.x, lo.y}, {hi.x, lo.y}, {hi.x, hi.y}, {lo.x, hi.y}}, 0, lo.z, hi.z, flags);
    m.name = "box";
    return m;
}

Mesh makeTorus(const glm::vec3& centre, float majorRadius, float minorRadius, int majorSegments,
               int minorSegments, uint32_t flags) {
    Mesh m;
    m.name = "torus";
    for (int i = 0; i < majorSegments; ++i) {
        float u = 2.0f * float(M_PI) * float(i) / float(majorSegments);
        for (int j = 0; j < minorSegments; ++j) {
            float v = 2.0f * float(M_PI) * float(j) / float(minorSegments);
            float r = majorRadius + minorRadius * std::cos(v);
            m.objectPositions.push_back(centre + glm::vec3(r * std::cos(u), r * std::sin(u),
                                                           minorRadius * std::sin(v)));
        }
    }
    auto at = [&](int i, int j) {
        return uint32_t((i % majorSegments) * minorSegments + (j % minorSegments));
    };
    for (int i = 0; i < majorSegments; ++i)
        for (int j = 0; j < minorSegments; ++j) {
            // Increasing u then increasing v is counter-clockwise seen from outside.
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    m.flags = flags;
    m.finalize();
    return m;
}

Mesh makeUvSphere(const glm::vec3& centre, float radius, int rings, int segments, uint32_t flags) {
    // The scene files' UV sphere (io/primitives.h), moved to `centre`.
    TriangleSoup soup = ss::makeUvSphere(radius, segments, rings);
    Mesh m;
    m.name = "sphere";
    for (const glm::vec3& p : soup.positions) m.objectPositions.push_back(centre + p);
    m.triangles = std::move(soup.triangles);
    m.flags = flags;
    m.finalize();
    return m;
}

Mesh makeMesh(std::vector<glm::vec3> positions, std::vector<glm::uvec3> triangles) {
    Mesh m;
    m.name = "test";
    m.objectPositions = std::move(positions);
    m.triangles = std::move(triangles);
    m.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    m.finalize();
    return m;
}

Mesh makeGround(float halfSize, float z, uint32_t flags) {
    Mesh m;
    m.name = "ground";
    m.objectPositions = {{-halfSize, -halfSize, z}, {halfSize, -halfSize, z},
                         {halfSize, halfSize, z}, {-halfSize, halfSize, z}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.flags = flags;
    m.finalize();
    return m;
}

Light makeDiskLight(const glm::vec3& position, float diameter, const std::string& name) {
    Light l;
    l.name = name;
    l.type = LightType::Disk;
    l.lightToWorld = glm::translate(glm::mat4(1.0f), position);  // local -Z is world down
    l.size = diameter;
    l.sizeY = diameter;
    return l;
}

Scene sceneCardWithHole(bool holeInTexture, int width, int height) {
    Scene s;
    s.addMesh(makeGround(6.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    Mesh card;
    card.name = "card";
    card.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    auto quad = [&](float x0, float y0, float x1, float y1) {
        const uint32_t b = uint32_t(card.objectPositions.size());
        for (glm::vec2 p : {glm::vec2(x0, y0), glm::vec2(x1, y0), glm::vec2(x1, y1), glm::vec2(x0, y1)})
            card.objectPositions.push_back({p.x, p.y, kCardHeight});
        card.triangles.push_back({b, b + 1, b + 2});
        card.triangles.push_back({b, b + 2, b + 3});
    };
    const float h = kCardHalf, o = kCardHoleHalf;
    if (holeInTexture) {
        for (int j = 0; j < 4; ++j)  // 4 x 4 cells: triangle edges cross the hole and the card
            for (int i = 0; i < 4; ++i)
                quad(-h + 0.5f * float(i), -h + 0.5f * float(j), -h + 0.5f * float(i + 1), -h + 0.5f * float(j + 1));
    } else {
        quad(-h, -h, h, -o), quad(-h, o, h, h), quad(-h, -o, -o, o), quad(o, -o, h, o);
    }
    card.finalize();
    MeshAlpha alpha;
    for (const glm::uvec3& t : card.triangles)
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = card.positions[t[k]];
            alpha.cornerUvs.push_back((glm::vec2(p.x, p.y) + h) / (2.0f * h));
        }
    AlphaMaterial hole;
    hole.width = hole.height = 8;
    hole.filter = AlphaFilter::Closest;
    hole.wrap = AlphaWrap::Extend;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) hole.texels.push_back(i >= 2 && i < 6 && j >= 2 && j < 6 ? 0.0f : 1.0f);
    alpha.materials.push_back(std::move(hole));
    const int index = s.addMesh(std::move(card));
    if (holeInTexture) s.setMeshAlpha(index, std::move(alpha));
    s.addLight(makeDiskLight({1.5f, 0.0f, 4.0f}, 0.5f));
    s.setCamera(makeLookAtCamera({0.0f, 0.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, glm::radians(35.0f),
                                 width, height, 0.1f, 50.0f));
    return s;
}

Camera makeTopCamera(int width, int height) {
    return makeLookAtCamera({0.0f, -2.5f, 8.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                            glm::radians(45.0f), width, height, 0.1f, 50.0f);
}

namespace {

constexpr uint32_t kOccluder = SS_MESH_CAST;
constexpr uint32_t kGround = SS_MESH_CAST | SS_MESH_RECEIVE;

Scene withGroundAndLight(const SceneParams& p) {
    Scene s;
    s.addMesh(makeGround(8.0f, 0.0f, kGround));
    s.addLight(makeDiskLight({p.lightShift.x, p.lightShift.y, p.lightHeight}, p.lightDiameter));
    Camera camera = makeTopCamera(p.width, p.height);
    if (p.cameraZoom != 1.0f)
        camera = makeLookAtCamera({0.0f, -2.5f, 8.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                  2.0f * std::atan(std::tan(glm::radians(22.5f)) / p.cameraZoom),
                                  p.width, p.height, 0.1f, 50.0f);
    s.setCamera(camera);
    return s;
}

}  // namespace

Scene sceneBox(const SceneParams& p) {
    Scene s = withGroundAndLight(p);
    float z = p.occluderLift;
    s.addMesh(makeBox({-0.6f, -0.6f, 0.8f + z}, {0.6f, 0.6f, 1.2f + z}, kOccluder));
    return s;
}

Scene sceneConcave(const SceneParams& p) {
    Scene s = withGroundAndLight(p);
    float z = p.occluderLift;
    // An L: 1.6 on a side, arms 0.6 wide; vertex 3 is the reflex corner.
    std::vector<glm::vec2> l = {{-0.8f, -0.8f}, {0.8f, -0.8f}, {0.8f, -0.2f},
                                {-0.2f, -0.2f}, {-0.2f, 0.8f}, {-0.8f, 0.8f}};
    Mesh m = makePrism(l, 3, 0.9f + z, 1.2f + z, kOccluder);
    m.name = "L";
    s.addMesh(std::move(m));
    return s;
}

Scene sceneOverlapping(const SceneParams& p) {
    Scene s = withGroundAndLight(p);
    float z = p.occluderLift;
    s.addMesh(makeBox({-0.9f, -0.5f, 0.5f + z}, {0.2f, 0.5f, 0.7f + z}, kOccluder));
    s.addMesh(makeBox({-0.1f, -0.3f, 1.6f + z}, {0.7f, 0.5f, 1.8f + z}, kOccluder));
    return s;
}

Scene sceneTorus(const SceneParams& p) {
    Scene s = withGroundAndLight(p);
    s.addMesh(makeTorus({0.0f, 0.0f, 1.2f + p.occluderLift}, 0.8f, 0.25f, 32, 16, kOccluder));
    return s;
}

std::vector<NamedScene> sharedScenes(const SceneParams& p) {
    std::vector<NamedScene> out;
    out.push_back({"box", sceneBox(p)});
    out.push_back({"concave", sceneConcave(p)});
    out.push_back({"overlapping", sceneOverlapping(p)});
    out.push_back({"torus", sceneTorus(p)});
    return out;
}

bool quickTests() {
    const char* q = std::getenv("SS_TEST_QUICK");
    return q && *q && std::string(q) != "0";
}

ss_status statusOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.status();
    }
    return SS_OK;
}

}  // namespace ss::test
