// How light links travel in scene files: mesh indices or unique mesh names, resolved after the meshes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene_file_links.h"

#include <optional>
#include <string>
#include <vector>

#include "core/error.h"

namespace ss {
namespace {

std::optional<std::vector<int>> readMeshSet(const JsonNode& light, const char* key, const Scene& scene) {
    if (!light.has(key)) return std::nullopt;
    const JsonNode items = light.at(key);
    const auto& meshes = scene.meshes();
    std::vector<int> out;
    for (size_t i = 0; i < items.size(); ++i) {
        const JsonNode item = items.at(i);
        if (item.value().is_string()) {
            const std::string name = item.string();
            int found = -1;
            for (size_t m = 0; m < meshes.size(); ++m) {
                if (meshes[m].name != name) continue;
                if (found >= 0) item.fail("two meshes are named '" + name + "' (name the mesh by its index)");
                found = int(m);
            }
            if (found < 0) item.fail("no mesh is named '" + name + "'");
            out.push_back(found);
        } else {
            out.push_back(int(item.integer(0, int64_t(meshes.size()) - 1)));
        }
    }
    return out;
}

}  // namespace

void readLightLinks(const JsonNode& lights, Scene& scene) {
    for (size_t i = 0; i < lights.size(); ++i) {
        const JsonNode light = lights.at(i);
        LightLinks links;
        links.receivers = readMeshSet(light, "receivers", scene);
        links.blockers = readMeshSet(light, "blockers", scene);
        if (!links.linked()) continue;
        try {
            scene.setLightLinks(int(i), std::move(links));
        } catch (const Error& e) {
            throw Error(e.status(), light.message(e.what()));
        }
    }
}

void writeLightLinks(const Light& light, nlohmann::json& object) {
    if (light.links.receivers) object["receivers"] = *light.links.receivers;
    if (light.links.blockers) object["blockers"] = *light.links.blockers;
}

}  // namespace ss
