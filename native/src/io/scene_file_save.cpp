// How a Scene is written as a scene file: matrices for lights and camera, meshes (object-space
// vertices and their transform) inline or, when big, as raw little-endian files beside it.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/scene_file.h"
#include "io/scene_file_links.h"
#include "io/scene_file_materials.h"

namespace ss {

namespace {

namespace fs = std::filesystem;

nlohmann::json matrixJson(const glm::mat4& m) {
    nlohmann::json a = nlohmann::json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) a.push_back(m[c][r]);
    return a;
}

void writeBytes(const std::string& path, const void* data, size_t size) {
    writeAtomically(path, [&](const std::string& temp) {
        std::ofstream out(temp, std::ios::binary);
        if (!out) fail(SS_ERROR_IO, "cannot write '" + path + "': " + std::strerror(errno));
        out.write(static_cast<const char*>(data), std::streamsize(size));
        out.close();
        if (!out) fail(SS_ERROR_IO, "cannot write '" + path + "': " + std::strerror(errno));
    });
}

nlohmann::json lightJson(const Light& l) {
    return {{"name", l.name},           {"type", lightTypeName(l.type)},
            {"matrix", matrixJson(l.lightToWorld)},
            {"size", l.size},           {"size_y", l.sizeY},
            {"radius", l.radius},       {"angle", l.angle},
            {"spot_size", l.spotSize},  {"spot_blend", l.spotBlend},
            {"cast_shadows", l.castShadows}};
}

}  // namespace

void saveSceneFile(const Scene& scene, const std::string& path, size_t inlineVertexLimit) {
    nlohmann::json root;
    root["format"] = "softshadow-scene";
    root["version"] = kSceneFormatVersion;
    root["view_layer"] = scene.viewLayer();
    if (scene.hasCamera()) {
        const Camera& c = scene.camera();
        root["camera"] = {{"world_to_camera", matrixJson(c.worldToCamera)},
                          {"projection", matrixJson(c.projection)},
                          {"width", c.width},
                          {"height", c.height},
                          {"pixel_aspect", c.pixelAspect}};
    }
    root["lights"] = nlohmann::json::array();
    for (const Light& l : scene.lights()) {
        nlohmann::json j = lightJson(l);
        writeLightLinks(l, j);
        root["lights"].push_back(std::move(j));
    }

    fs::path target(path);
    std::string stem = target.stem().string();
    root["meshes"] = nlohmann::json::array();
    const auto& meshes = scene.meshes();
    for (size_t i = 0; i < meshes.size(); ++i) {
        const Mesh& m = meshes[i];
        nlohmann::json j = {{"name", m.name},
                            {"cast", m.casts()},
                            {"receive", m.receives()},
                            {"thin", (m.flags & SS_MESH_THIN) != 0},
                            {"camera_visible", (m.flags & SS_MESH_CAMERA_HIDDEN) == 0}};
        if (m.objectPositions.size() > inlineVertexLimit) {
            std::string base = stem + "." + std::to_string(i);
            std::string pos = base + ".positions.f32", tri = base + ".triangles.u32";
            writeBytes((target.parent_path() / pos).string(), m.objectPositions.data(),
                       m.objectPositions.size() * sizeof(glm::vec3));
            writeBytes((target.parent_path() / tri).string(), m.triangles.data(),
                       m.triangles.size() * sizeof(glm::uvec3));
            j["positions_file"] = pos;
            j["triangles_file"] = tri;
        } else {
            nlohmann::json p = nlohmann::json::array(), t = nlohmann::json::array();
            for (const glm::vec3& v : m.objectPositions) p.push_back(v.x), p.push_back(v.y), p.push_back(v.z);
            for (const glm::uvec3& f : m.triangles) t.push_back(f.x), t.push_back(f.y), t.push_back(f.z);
            j["positions"] = std::move(p);
            j["triangles"] = std::move(t);
        }
        if (m.transformed()) j["transform"] = matrixJson(m.objectToWorld);
        if (m.alpha) j["materials"] = meshAlphaJson(*m.alpha);
        root["meshes"].push_back(std::move(j));
    }
    std::string text = root.dump(1) + "\n";
    writeBytes(path, text.data(), text.size());
}

}  // namespace ss
