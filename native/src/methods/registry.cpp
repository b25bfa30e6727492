// Which methods exist (the contract names), which of them `auto` may try and its fallback rule.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>

#include "core/error.h"
#include "methods/method.h"
#include "methods/sweep/receiver.h"

namespace ss {

// One factory per method, defined in that method's own file.
std::unique_ptr<Method> makeShadowMapMethod();
std::unique_ptr<Method> makeReferenceMethod();
std::unique_ptr<Method> makeSweepMethod();
std::unique_ptr<Method> makePcssMethod();
std::unique_ptr<Method> makePenumbraMapMethod();
std::unique_ptr<Method> makeOcclusionTexturesMethod();
std::unique_ptr<Method> makeDbufferMethod();

namespace {
struct Entry {
    const char* name;
    std::unique_ptr<Method> (*make)();
};
const std::vector<Entry>& entries() {
    static const std::vector<Entry> table = {
        {"shadow_map", makeShadowMapMethod},
        {"pcss", makePcssMethod},
        {"dbuffer", makeDbufferMethod},
        {"sweep", makeSweepMethod},
        {"penumbra_map", makePenumbraMapMethod},
        {"occlusion_textures", makeOcclusionTexturesMethod},
        {"reference", makeReferenceMethod},
    };
    return table;
}
}  // namespace

std::unique_ptr<Method> createMethod(const std::string& name) {
    for (const Entry& e : entries())
        if (name == e.name) return e.make();
    std::string known;
    for (const Entry& e : entries()) known += std::string(known.empty() ? "" : ", ") + e.name;
    fail(SS_ERROR_INVALID_ARGUMENT, "unknown method '" + name + "' (known: " + known + ", auto)");
}

namespace {
// Whether every point of the light lies on the same side of every face: then the mesh's only
// silhouette, seen from anywhere on the light, is its border.
bool facesOneSideOfLight(const Mesh& mesh, const Light& light) {
    const glm::dvec3 centre(light.position());
    const double reach = light.type == LightType::Point || light.type == LightType::Spot
                             ? double(light.radius)
                             : std::sqrt(double(glm::dot(light.halfAxisX(), light.halfAxisX())) +
                                         double(glm::dot(light.halfAxisY(), light.halfAxisY())));
    const glm::dvec3 toSun = -glm::dvec3(light.direction());
    const double sunSlack = std::sin(double(light.sunHalfAngle()));
    int side = 0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double length = glm::length(n);
        if (!(length > 0.0)) continue;  // a degenerate face has no side
        const double distance = light.type == LightType::Sun ? glm::dot(n, toSun) : glm::dot(n, centre - a);
        const double slack = length * (light.type == LightType::Sun ? sunSlack : reach);
        const int faceSide = distance > slack ? 1 : distance < -slack ? -1 : 0;
        if (faceSide == 0 || (side != 0 && faceSide != side)) return false;
        side = faceSide;
    }
    return true;
}

// An open caster whose faces all see the light from one side (a floor, a wall, a curved ground
// or backdrop: Blender lets every object cast by default) is not a problem for the volumes:
// its only silhouette is its border, whose volumes point away from the light, behind it. Any
// other open or non-manifold caster is.
bool castersClosedForVolumes(const Scene& scene, int lightIndex) {
    const Light& light = scene.light(lightIndex);
    for (size_t i = 0; i < scene.meshes().size(); ++i) {
        const Mesh& m = scene.meshes()[i];
        if (scene.castsFor(int(i), lightIndex) && !m.report.closedManifold() && !isPlanarMesh(m) &&
            !facesOneSideOfLight(m, light))
            return false;
    }
    return true;
}
}  // namespace

std::vector<std::string> autoCandidates(const Scene& scene, int lightIndex) {
    const bool closed = castersClosedForVolumes(scene, lightIndex);
    std::vector<std::string> out;
    for (const std::string& name : methodNames()) {
        if (name == "reference") continue;  // the truth itself: not an interactive method
        // dbuffer's volumes assume closed 2-manifold casters (docs/methods/dbuffer.md).
        if (name == "dbuffer" && !closed) continue;
        out.push_back(name);
    }
    return out;
}

bool autoPriorKeeps(const Scene& scene, int lightIndex, const std::string& method) {
    const LightType type = scene.light(lightIndex).type;
    const bool rectangular = type == LightType::Square || type == LightType::Rectangle;
    const bool round = type == LightType::Disk || type == LightType::Ellipse || type == LightType::Point ||
                       type == LightType::Spot;
    if (method == "dbuffer") return round;
    if (method == "occlusion_textures") return rectangular;
    return true;
}

std::string chooseAutoMethodByShape(const Scene& scene, int lightIndex) {
    // Used only where the sparse check cannot run (docs/methods/README.md): each light gets the
    // method whose paper models its shape, unless the scene breaks that method's assumptions.
    const Light& light = scene.light(lightIndex);
    const bool castersClosed = castersClosedForVolumes(scene, lightIndex);
    switch (light.type) {
        case LightType::Square:
        case LightType::Rectangle:
            // Occlusion textures are built for rectangular lights and need no closed meshes.
            return "occlusion_textures";
        case LightType::Disk:
        case LightType::Ellipse:
        case LightType::Point:
        case LightType::Spot:
            // Umbra/penumbra volumes give correct boundaries for disks, but their extrusion
            // assumes closed 2-manifold casters; PCSS accepts any triangle soup.
            return castersClosed ? "dbuffer" : "pcss";
        case LightType::Sun: return "pcss";
    }
    return "pcss";
}

}  // namespace ss
