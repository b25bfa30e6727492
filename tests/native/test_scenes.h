// Which small code-built scenes every method's quality test renders (shared; additive edits only).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/light.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "softshadow/softshadow.h"

namespace ss::test {

// A mesh named "test" from positions and triangles, casting and receiving, finalized.
Mesh makeMesh(std::vector<glm::vec3> positions, std::vector<glm::uvec3> triangles);
// Closed, outward-wound meshes (Mesh::finalize() already run).
Mesh makeBox(const glm::vec3& lo, const glm::vec3& hi, uint32_t flags);
// A prism over a counter-clockwise simple polygon, caps triangulated as a fan from
// `fanVertex` (which must see every other vertex: any vertex of a convex polygon, the reflex
// vertex of an L).
Mesh makePrism(const std::vector<glm::vec2>& polygon, size_t fanVertex, float z0, float z1,
               uint32_t flags);
Mesh makeTorus(const glm::vec3& centre, float majorRadius, float minorRadius, int majorSegments,
               int minorSegments, uint32_t flags);
// A UV sphere with flat facets: `rings` bands from pole to pole, `segments` around; outward CCW.
Mesh makeUvSphere(const glm::vec3& centre, float radius, int rings, int segments, uint32_t flags);
// The receiver: an upward-facing square at height z (two triangles, open edges).
Mesh makeGround(float halfSize, float z, uint32_t flags);

// A disk light of the given diameter at `position`, facing straight down (Blender's default).
Light makeDiskLight(const glm::vec3& position, float diameter, const std::string& name = "Disk");
// The shared camera: looking down at the origin from above and slightly to the -y side.
Camera makeTopCamera(int width = 160, int height = 120);

// Parameters of the shared scenes (defaults are what the quality tests use).
struct SceneParams {
    float lightDiameter = 1.5f;
    float lightHeight = 4.0f;
    float occluderLift = 0.0f;  // raises the occluder(s) by this much (farther from the ground)
    int width = 160, height = 120;
    // Added later (keep at the end: tests build SceneParams positionally). The light moved
    // sideways in x, y, so its shadow falls beside the occluder rather than under it; and the
    // camera's field of view divided by this zoom.
    glm::vec2 lightShift{0.0f, 0.0f};
    float cameraZoom = 1.0f;
};

// Box (1.2 x 1.2 x 0.4, top at z = 1.2) over a ground plane at z = 0.
Scene sceneBox(const SceneParams& p = {});
// A concave L prism (closed manifold) over the ground.
Scene sceneConcave(const SceneParams& p = {});
// Two boxes at different heights whose shadows overlap.
Scene sceneOverlapping(const SceneParams& p = {});
// A torus lying flat over the ground (its hole lets light through).
Scene sceneTorus(const SceneParams& p = {});

// A card the camera sees the ground through: a receiving, casting 2 x 2 square at z = 1 (mesh 1,
// "card") whose middle (|x|, |y| < 0.5) is a hole, over the ground (mesh 0, casting and
// receiving), a disk light to the +x side so the ground seen through the hole is partly in the
// card's shadow, and a camera looking straight down through the hole. With `holeInTexture` the
// card is whole and the hole is its alpha texture (8 x 8 texels, 0 in the middle 4 x 4, Closest,
// Extend; UVs (0, 0) .. (1, 1) over the card); else the hole is cut out of its geometry.
Scene sceneCardWithHole(bool holeInTexture, int width = 128, int height = 96);
inline constexpr float kCardHoleHalf = 0.5f, kCardHalf = 1.0f, kCardHeight = 1.0f;

struct NamedScene {
    std::string name;
    Scene scene;
};
// Every shared scene with its name, light 0 being its disk light.
std::vector<NamedScene> sharedScenes(const SceneParams& p = {});

// True when SS_TEST_QUICK is set (sanitizer runs): tests shrink sizes and sample counts.
bool quickTests();

// The status `f` throws as ss::Error, or SS_OK when it returns.
ss_status statusOf(const std::function<void()>& f);

}  // namespace ss::test
