// How a scene file is parsed into a Scene: camera, lights, meshes (inline, external, primitive).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene_file.h"
#include "io/scene_file_links.h"
#include "io/scene_file_materials.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/camera.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "io/json_node.h"
#include "io/input_file.h"
#include "io/json_reader.h"
#include "io/primitives.h"
#include "softshadow/softshadow.h"

namespace ss {

static_assert(std::endian::native == std::endian::little, "external mesh files are little-endian");

namespace {

namespace fs = std::filesystem;

// Where an external mesh file named in a scene lies: relative to the scene's folder and inside
// it, so a scene from elsewhere cannot make the loader read arbitrary files.
fs::path externalFilePath(const JsonNode& node, const std::string& baseDir) {
    std::string name = node.string();
    fs::path rel(name);
    if (name.empty()) node.fail("is empty (expected a file name relative to the scene's folder)");
    if (rel.is_absolute()) node.fail("'" + name + "' is an absolute path (allowed: a path inside the scene's folder)");
    for (const fs::path& part : rel)
        if (part == "..") node.fail("'" + name + "' leaves the scene's folder ('..'; allowed: a path inside it)");
    std::error_code ec;
    fs::path base = fs::weakly_canonical(fs::path(baseDir), ec);
    fs::path full = fs::weakly_canonical(fs::path(baseDir) / rel, ec);
    if (!ec) {
        auto [b, f] = std::mismatch(base.begin(), base.end(), full.begin(), full.end());
        if (b != base.end())
            node.fail("'" + name + "' leads out of the scene's folder through a symlink (allowed: a path inside it)");
    }
    return fs::path(baseDir) / rel;
}

template <class T>
std::vector<T> readRaw(const JsonNode& node, const std::string& baseDir) {
    fs::path p = externalFilePath(node, baseDir);
    std::string bytes;
    try {
        bytes = readInputFile(p.string(), "mesh file", kMaxMeshFileBytes);
    } catch (const Error& e) {
        node.fail(e.what());
    }
    if (bytes.empty()) node.fail("'" + p.string() + "' is empty (a mesh file needs at least one triangle)");
    if (bytes.size() % (3 * sizeof(T)) != 0)
        node.fail("'" + p.string() + "' has " + std::to_string(bytes.size()) +
                  " bytes, not a whole number of 3 x " + std::to_string(sizeof(T)) + "-byte values");
    std::vector<T> out(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
}

Camera readCamera(const JsonNode& n) {
    Camera c;
    if (n.has("world_to_camera")) {
        n.expectKeys({"world_to_camera", "projection", "width", "height", "pixel_aspect", "comment"});
        c.worldToCamera = n.at("world_to_camera").mat4();
        c.projection = n.at("projection").mat4();
        c.width = int(n.at("width").integer(1, kMaxCameraSide));
        c.height = int(n.at("height").integer(1, kMaxCameraSide));
        c.pixelAspect = n.real("pixel_aspect", 1.0f);
        return c;
    }
    n.expectKeys({"look_from", "look_at", "up", "fov_y_degrees", "near", "far", "width", "height",
                  "pixel_aspect", "comment"});
    glm::vec3 from = n.at("look_from").vec3(), to = n.at("look_at").vec3();
    glm::vec3 up = n.has("up") ? n.at("up").vec3() : glm::vec3(0, 0, 1);
    float fov = n.real("fov_y_degrees", 39.6f);  // Blender's default 50 mm lens on a 36 mm sensor
    if (!(fov > 0.0f && fov < 180.0f)) n.at("fov_y_degrees").fail("must be in (0, 180) degrees");
    float nearClip = n.real("near", 0.1f), farClip = n.real("far", 1000.0f);
    if (!(nearClip > 0.0f && farClip > nearClip)) n.fail("needs 0 < near < far");
    if (glm::length(to - from) <= 0.0f) n.fail("look_from and look_at are the same point");
    if (glm::length(glm::cross(glm::normalize(to - from), up)) < 1e-6f)
        n.fail("up is parallel to the viewing direction");
    int w = int(n.at("width").integer(1, kMaxCameraSide)), h = int(n.at("height").integer(1, kMaxCameraSide));
    float pixelAspect = n.real("pixel_aspect", 1.0f);
    if (!(pixelAspect > 0.0f)) n.at("pixel_aspect").fail("must be greater than zero");
    c = makeLookAtCamera(from, to, up, glm::radians(fov), w, h, nearClip, farClip);
    // Pixels pixelAspect times wider than tall show a wider picture at the same height.
    c.projection = glm::perspective(glm::radians(fov), float(w) * pixelAspect / float(h), nearClip, farClip);
    c.pixelAspect = pixelAspect;
    return c;
}

// A frame whose local -Z is `direction` and whose local +Y leans towards `up`.
glm::mat4 frameFromDirection(const JsonNode& n, const glm::vec3& position, glm::vec3 direction,
                             const glm::vec3* upHint) {
    if (!(glm::length(direction) > 0.0f)) n.at("direction").fail("must not be zero");
    glm::vec3 z = -glm::normalize(direction);
    glm::vec3 up = upHint ? *upHint : glm::vec3(0, 0, 1);
    if (glm::length(glm::cross(up, z)) < 1e-6f) {
        if (upHint) n.at("up").fail("is parallel to direction");
        up = glm::vec3(0, 1, 0);
    }
    glm::vec3 x = glm::normalize(glm::cross(up, z));
    glm::vec3 y = glm::cross(z, x);
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(x, 0);
    m[1] = glm::vec4(y, 0);
    m[2] = glm::vec4(z, 0);
    m[3] = glm::vec4(position, 1);
    return m;
}

Light readLight(const JsonNode& n) {
    n.expectKeys({"name", "type", "matrix", "position", "direction", "up", "size", "size_y", "radius",
                  "angle", "spot_size", "spot_blend", "cast_shadows", "receivers", "blockers", "comment"});
    Light l;
    l.name = n.at("name").string();
    std::string type = n.at("type").string();
    if (!parseLightType(type, &l.type))
        n.at("type").fail("unknown light type '" + type +
                          "' (expected disk, ellipse, square, rectangle, point, spot or sun)");
    if (n.has("matrix")) {
        if (n.has("position") || n.has("direction")) n.fail("give either matrix or position/direction, not both");
        l.lightToWorld = n.at("matrix").mat4();
    } else {
        glm::vec3 pos = n.has("position") ? n.at("position").vec3() : glm::vec3(0.0f);
        if (l.type != LightType::Sun && !n.has("position")) n.at("position");  // throws "is missing"
        glm::vec3 dir = n.at("direction").vec3();
        glm::vec3 up;
        if (n.has("up")) up = n.at("up").vec3();
        l.lightToWorld = frameFromDirection(n, pos, dir, n.has("up") ? &up : nullptr);
    }
    // Blender's defaults for what a file leaves out.
    l.size = n.real("size", 1.0f);
    l.sizeY = n.real("size_y", l.size);
    l.radius = n.real("radius", 0.25f);
    l.angle = n.real("angle", 0.00918043f);  // 0.526 degrees
    l.spotSize = n.real("spot_size", 0.785398f);  // 45 degrees
    l.spotBlend = n.real("spot_blend", 0.15f);
    l.castShadows = n.boolean("cast_shadows", true);
    return l;
}

glm::mat4 readTransform(const JsonNode& n) {
    if (n.has("transform")) {
        if (n.has("translate") || n.has("rotate_deg") || n.has("scale"))
            n.fail("give either transform or translate/rotate_deg/scale, not both");
        const glm::mat4 m = n.at("transform").mat4();
        if (glm::vec4(m[0][3], m[1][3], m[2][3], m[3][3]) != glm::vec4(0, 0, 0, 1))
            n.at("transform").fail("is not affine: its last row (elements 3, 7, 11, 15) must be 0 0 0 1");
        return m;
    }
    glm::mat4 m(1.0f);
    if (n.has("translate")) m = glm::translate(m, n.at("translate").vec3());
    if (n.has("rotate_deg")) {
        // Blender's XYZ Euler: X first, then Y, then Z, about the world axes.
        glm::vec3 r = glm::radians(n.at("rotate_deg").vec3());
        m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
        m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
        m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
    }
    if (n.has("scale")) {
        JsonNode s = n.at("scale");
        glm::vec3 k = s.value().is_array() ? s.vec3() : glm::vec3(s.real());
        if (k.x == 0.0f || k.y == 0.0f || k.z == 0.0f) s.fail("a scale of zero flattens the mesh");
        m = glm::scale(m, k);
    }
    return m;
}

int positiveCount(const JsonNode& n, const char* key, int fallback, int lo) {
    return int(n.integer(key, fallback, lo, 4096));
}

float positiveSize(const JsonNode& n, const char* key, float fallback) {
    float v = n.real(key, fallback);
    if (!(v > 0.0f)) n.at(key).fail("must be greater than zero");
    return v;
}

// What the meshes of one scene file have taken so far, against a limit of triangles and of
// vertices (kMaxSceneTriangles for users); each mesh's share is taken before anything is
// allocated for it.
struct GeometryBudget {
    int64_t limit = kMaxSceneTriangles;
    int64_t triangles = 0, vertices = 0;
    void take(const JsonNode& n, int64_t moreTriangles, int64_t moreVertices) {
        triangles += moreTriangles;
        vertices += moreVertices;
        if (triangles <= limit && vertices <= limit) return;
        char text[400];
        std::snprintf(text, sizeof text,
                      "the scene's meshes would reach %lld triangles and %lld vertices with this one, past the "
                      "budget of %lld of each for a scene file (about %.0f GB at %.0f bytes a triangle; "
                      "docs/reliability.md)",
                      (long long)triangles, (long long)vertices, (long long)limit,
                      double(limit) * kBudgetBytesPerTriangle / 1e9, kBudgetBytesPerTriangle);
        n.fail(text);
    }
};

TriangleSoup readPrimitive(const JsonNode& n, GeometryBudget& budget) {
    std::string type = n.at("type").string();
    if (type == "plane") {
        n.expectKeys({"type", "size", "size_x", "size_y", "subdivisions"});
        float size = positiveSize(n, "size", 2.0f);
        const int k = positiveCount(n, "subdivisions", 1, 1);
        budget.take(n, 2 * int64_t(k) * k, int64_t(k + 1) * (k + 1));
        return makePlane(positiveSize(n, "size_x", size), positiveSize(n, "size_y", size), k);
    }
    if (type == "box") {
        n.expectKeys({"type", "size", "subdivisions"});
        glm::vec3 size(2.0f);
        if (n.has("size")) {
            JsonNode s = n.at("size");
            size = s.value().is_array() ? s.vec3() : glm::vec3(s.real());
            if (!(size.x > 0 && size.y > 0 && size.z > 0)) s.fail("must be greater than zero");
        }
        const int k = positiveCount(n, "subdivisions", 1, 1);
        budget.take(n, 12 * int64_t(k) * k, 6 * int64_t(k + 1) * (k + 1));
        return makeBox(size, k);
    }
    if (type == "uv_sphere") {
        n.expectKeys({"type", "radius", "segments", "rings"});
        const int segments = positiveCount(n, "segments", 32, 3), rings = positiveCount(n, "rings", 16, 2);
        budget.take(n, 2 * int64_t(segments) * rings, int64_t(segments) * rings + 2);
        return makeUvSphere(positiveSize(n, "radius", 1.0f), segments, rings);
    }
    if (type == "disk") {
        n.expectKeys({"type", "radius", "segments"});
        const int segments = positiveCount(n, "segments", 32, 3);
        budget.take(n, segments, segments + 1);
        return makeDisk(positiveSize(n, "radius", 1.0f), segments);
    }
    if (type == "torus") {
        n.expectKeys({"type", "major_radius", "minor_radius", "major_segments", "minor_segments"});
        float major = positiveSize(n, "major_radius", 1.0f), minor = positiveSize(n, "minor_radius", 0.25f);
        if (!(minor < major)) n.fail("minor_radius must be smaller than major_radius");
        const int u = positiveCount(n, "major_segments", 48, 3), v = positiveCount(n, "minor_segments", 12, 3);
        budget.take(n, 2 * int64_t(u) * v, int64_t(u) * v);
        return makeTorus(major, minor, u, v);
    }
    if (type == "cylinder") {
        n.expectKeys({"type", "radius", "depth", "segments"});
        const int segments = positiveCount(n, "segments", 32, 3);
        budget.take(n, 4 * int64_t(segments), 2 * int64_t(segments) + 2);
        return makeCylinder(positiveSize(n, "radius", 1.0f), positiveSize(n, "depth", 2.0f), segments);
    }
    n.at("type").fail("unknown primitive '" + type + "' (expected plane, box, uv_sphere, disk, torus or cylinder)");
}

// The size of a mesh file as the budget sees it (0 when it cannot be told: readRaw then says why).
int64_t tripletsIn(const JsonNode& node, const std::string& baseDir) {
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(externalFilePath(node, baseDir), ec);
    return ec ? 0 : int64_t(bytes / 12);
}

TriangleSoup readGeometry(const JsonNode& n, const std::string& baseDir, GeometryBudget& budget) {
    int kinds = int(n.has("positions") || n.has("triangles")) +
                int(n.has("positions_file") || n.has("triangles_file")) + int(n.has("primitive"));
    if (kinds != 1)
        n.fail("needs exactly one geometry: positions+triangles, positions_file+triangles_file, or primitive");
    TriangleSoup soup;
    std::vector<float> xyz;
    std::vector<uint32_t> idx;
    if (n.has("primitive")) {
        soup = readPrimitive(n.at("primitive"), budget);
    } else if (n.has("positions_file") || n.has("triangles_file")) {
        budget.take(n, tripletsIn(n.at("triangles_file"), baseDir), tripletsIn(n.at("positions_file"), baseDir));
        xyz = readRaw<float>(n.at("positions_file"), baseDir);
        idx = readRaw<uint32_t>(n.at("triangles_file"), baseDir);
        for (size_t i = 0; i < xyz.size(); ++i)
            if (!std::isfinite(xyz[i]))
                n.at("positions_file").fail("value " + std::to_string(i) + " (vertex " +
                                            std::to_string(i / 3) + ") is not finite");
    } else {
        JsonNode p = n.at("positions"), t = n.at("triangles");
        budget.take(n, int64_t(t.size() / 3), int64_t(p.size() / 3));
        xyz = p.reals();
        if (xyz.size() % 3) p.fail("has " + std::to_string(xyz.size()) + " numbers, not a multiple of 3");
        size_t count = t.size();
        if (count % 3) t.fail("has " + std::to_string(count) + " indices, not a multiple of 3");
        idx.resize(count);
        for (size_t i = 0; i < count; ++i) {
            const nlohmann::json& e = t.value()[i];
            if (e.is_number_unsigned()) {
                uint64_t v = e.get<uint64_t>();
                if (v <= 0xffffffffu) {
                    idx[i] = uint32_t(v);
                    continue;
                }
            }
            idx[i] = uint32_t(t.at(i).integer(0, 0xfffffffe));
        }
        // Name the JSON element of the first bad index (Mesh::finalize would name the triangle).
        size_t vertices = xyz.size() / 3;
        for (size_t i = 0; i < idx.size(); ++i)
            if (idx[i] >= vertices) {
                std::ostringstream m;
                m << "vertex index " << idx[i] << " is out of range (the mesh has " << vertices
                  << " vertices)";
                t.at(i).fail(m.str(), SS_ERROR_INVALID_SCENE);
            }
    }
    if (!n.has("primitive")) {
        soup.positions.resize(xyz.size() / 3);
        std::memcpy(soup.positions.data(), xyz.data(), soup.positions.size() * sizeof(glm::vec3));
        soup.triangles.resize(idx.size() / 3);
        std::memcpy(soup.triangles.data(), idx.data(), soup.triangles.size() * sizeof(glm::uvec3));
    }
    return soup;
}

Mesh readMesh(const JsonNode& n, const std::string& baseDir, GeometryBudget& budget) {
    n.expectKeys({"name", "cast", "receive", "thin", "camera_visible", "positions", "triangles", "positions_file",
                  "triangles_file", "primitive", "transform", "translate", "rotate_deg", "scale",
                  "materials", "comment"});
    Mesh m;
    m.name = n.at("name").string();
    m.flags = (n.boolean("cast", true) ? SS_MESH_CAST : 0u) |
              (n.boolean("receive", true) ? SS_MESH_RECEIVE : 0u) |
              (n.boolean("thin", false) ? SS_MESH_THIN : 0u) |
              (n.boolean("camera_visible", true) ? 0u : SS_MESH_CAMERA_HIDDEN);
    TriangleSoup soup = readGeometry(n, baseDir, budget);
    m.objectPositions = std::move(soup.positions);
    m.triangles = std::move(soup.triangles);
    m.objectToWorld = readTransform(n);
    if (n.has("materials")) m.alpha = std::make_shared<const MeshAlpha>(readMeshAlpha(n.at("materials")));
    return m;
}

// Adds to the scene, putting the JSON path in front of what the scene model rejects.
template <class F>
void addWithPath(const JsonNode& n, F&& add) {
    try {
        add();
    } catch (const Error& e) {
        throw Error(e.status(), n.message(e.what()));
    }
}

// Calls `read` on each element of the optional array `key` of `n`, refusing one of more than
// `most` elements before any is read.
template <class F>
void forEachElement(const JsonNode& n, const char* key, size_t most, F&& read) {
    if (!n.has(key)) return;
    JsonNode items = n.at(key);
    if (items.size() > most)
        items.fail("has " + std::to_string(items.size()) + " " + key + " (at most " + std::to_string(most) + ")");
    for (size_t i = 0; i < items.size(); ++i) read(items.at(i));
}

}  // namespace

Scene parseSceneText(const std::string& text, const std::string& baseDir, const std::string& shownName,
                     int64_t maxGeometry) {
    std::string where = "scene '" + shownName + "'";
    nlohmann::json root = parseJsonStrict(text, where);
    JsonNode r(root, where, "");
    r.expectKeys({"format", "version", "view_layer", "camera", "lights", "meshes", "metadata", "comment"});
    std::string format = r.at("format").string();
    if (format != "softshadow-scene")
        r.at("format").fail("expected \"softshadow-scene\", got \"" + format + "\"");
    int64_t version = r.at("version").integer(1, 1000000);
    if (version > kSceneFormatVersion)
        r.at("version").fail("version " + std::to_string(version) + " is newer than this softshadow reads (" +
                             std::to_string(kSceneFormatVersion) + ")");

    Scene scene;
    if (r.has("view_layer")) {
        JsonNode v = r.at("view_layer");
        std::string name = v.string();
        addWithPath(v, [&] { scene.setViewLayer(name); });
    }
    if (r.has("camera")) {
        JsonNode c = r.at("camera");
        Camera cam = readCamera(c);
        addWithPath(c, [&] { scene.setCamera(cam); });
    }
    forEachElement(r, "lights", kMaxLights, [&](const JsonNode& l) {
        Light light = readLight(l);
        addWithPath(l, [&] { scene.addLight(std::move(light)); });
    });
    GeometryBudget budget{maxGeometry};
    forEachElement(r, "meshes", kMaxMeshes, [&](const JsonNode& m) {
        Mesh mesh = readMesh(m, baseDir, budget);
        addWithPath(m, [&] { scene.addMesh(std::move(mesh)); });
    });
    if (r.has("lights")) readLightLinks(r.at("lights"), scene);  // they name meshes
    return scene;
}

Scene loadSceneFile(const std::string& path) {
    std::string text = readInputFile(path, "scene file", kMaxSceneFileBytes);
    std::string base = fs::path(path).parent_path().string();
    return parseSceneText(text, base.empty() ? "." : base, path);
}

}  // namespace ss
