// What `softshadow report` prints: each mesh's report, the lights (with their light and shadow
// links) and the camera of a scene file.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_common.h"

namespace ss::cli {

namespace {
const char* lightTypeText(ss_light_type t) {
    static const char* names[] = {"disk", "ellipse", "square", "rectangle", "point", "spot", "sun"};
    return int(t) >= 0 && int(t) < 7 ? names[int(t)] : "?";
}
// One link list of a light: null for every mesh (no linking), else the names of the linked
// meshes, in mesh order.
nlohmann::json linkNames(const std::vector<int32_t>* indices, const nlohmann::json& meshes) {
    if (!indices) return nullptr;
    nlohmann::json names = nlohmann::json::array();
    for (int32_t i : *indices) names.push_back(meshes.at(size_t(i))["mesh"]);
    return names;
}

// A light's blockers and receivers by mesh name (ss_scene_get_light_links).
std::pair<nlohmann::json, nlohmann::json> lightLinks(const ss_scene* scene, int32_t light, const nlohmann::json& meshes) {
    const int32_t meshCount = ss_scene_mesh_count(scene);
    std::vector<int32_t> blockers(size_t(meshCount) + 1), receivers(size_t(meshCount) + 1);
    int32_t blockerCount = 0, receiverCount = 0;
    check(ss_scene_get_light_links(scene, light, blockers.data(), int32_t(blockers.size()), &blockerCount,
                                   receivers.data(), int32_t(receivers.size()), &receiverCount));
    blockers.resize(size_t(std::max(blockerCount, 0)));
    receivers.resize(size_t(std::max(receiverCount, 0)));
    return {linkNames(blockerCount < 0 ? nullptr : &blockers, meshes),
            linkNames(receiverCount < 0 ? nullptr : &receivers, meshes)};
}

// "every mesh" or the names, comma-separated ("none" for an empty list).
std::string linkText(const nlohmann::json& names) {
    if (names.is_null()) return "every mesh";
    if (names.empty()) return "none";
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n.get<std::string>();
    return out;
}

}  // namespace

int runReport(const std::vector<std::string>& argv) {
    Args args(argv, {}, {"--json"});
    if (args.positional().size() != 1) throw CliError("report needs exactly one SCENE file");
    ss_scene* raw = nullptr;
    check(ss_scene_load(args.positional()[0].c_str(), &raw));
    std::unique_ptr<ss_scene, void (*)(ss_scene*)> scene(raw, ss_scene_destroy);

    nlohmann::json meshes = nlohmann::json::array();
    std::vector<char> buffer(1 << 16);
    for (int32_t i = 0; i < ss_scene_mesh_count(scene.get()); ++i) {
        check(ss_scene_mesh_report(scene.get(), i, buffer.data(), buffer.size()));
        meshes.push_back(nlohmann::json::parse(buffer.data()));
    }
    nlohmann::json lights = nlohmann::json::array();
    for (int32_t i = 0; i < ss_scene_light_count(scene.get()); ++i) {
        ss_light_desc d;
        check(ss_scene_get_light(scene.get(), i, &d));
        auto [blockers, receivers] = lightLinks(scene.get(), i, meshes);
        lights.push_back({{"name", d.name}, {"type", lightTypeText(d.type)},
                          {"cast_shadows", d.cast_shadows != 0}, {"blockers", blockers}, {"receivers", receivers}});
    }
    nlohmann::json camera = nullptr;
    ss_camera_desc cam;
    if (ss_scene_get_camera(scene.get(), &cam) == SS_OK)
        camera = {{"width", cam.width}, {"height", cam.height}, {"pixel_aspect", cam.pixel_aspect}};

    if (args.flag("--json")) {
        nlohmann::json out = {{"view_layer", ss_scene_view_layer(scene.get())},
                              {"meshes", meshes}, {"lights", lights}, {"camera", camera}};
        std::printf("%s\n", out.dump(2).c_str());
        return 0;
    }
    std::printf("%-24s %10s %12s %13s %11s  %s\n", "mesh", "open_edges", "non_manifold", "inconsistent",
                "degenerate", "closed manifold");
    for (const auto& m : meshes)
        std::printf("%-24s %10zu %12zu %13zu %11zu  %s\n", m["mesh"].get<std::string>().c_str(),
                    m["open_edges"].get<size_t>(), m["non_manifold_edges"].get<size_t>(),
                    m["inconsistent_edges"].get<size_t>(), m["degenerate_faces"].get<size_t>(),
                    m["closed_manifold"].get<bool>() ? "yes" : "no");
    for (const auto& l : lights) {
        std::printf("light  %-24s %-10s %s\n", l["name"].get<std::string>().c_str(),
                    l["type"].get<std::string>().c_str(),
                    l["cast_shadows"].get<bool>() ? "casts shadows" : "no shadows");
        std::printf("       shadowed by (blockers): %s\n", linkText(l["blockers"]).c_str());
        std::printf("       lights (receivers): %s\n", linkText(l["receivers"]).c_str());
    }
    if (camera.is_null()) std::printf("camera none\n");
    else std::printf("camera %dx%d, pixel aspect %g\n", cam.width, cam.height, cam.pixel_aspect);
    std::printf("view layer %s\n", ss_scene_view_layer(scene.get()));
    return 0;
}

}  // namespace ss::cli
