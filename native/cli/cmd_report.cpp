// What `softshadow report` prints: each mesh's report, the lights and the camera of a scene file.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli_common.h"

namespace ss::cli {

namespace {
const char* lightTypeText(ss_light_type t) {
    static const char* names[] = {"disk", "ellipse", "square", "rectangle", "point", "spot", "sun"};
    return int(t) >= 0 && int(t) < 7 ? names[int(t)] : "?";
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
        lights.push_back({{"name", d.name}, {"type", lightTypeText(d.type)},
                          {"cast_shadows", d.cast_shadows != 0}});
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
    for (const auto& l : lights)
        std::printf("light  %-24s %-10s %s\n", l["name"].get<std::string>().c_str(),
                    l["type"].get<std::string>().c_str(),
                    l["cast_shadows"].get<bool>() ? "casts shadows" : "no shadows");
    if (camera.is_null()) std::printf("camera none\n");
    else std::printf("camera %dx%d, pixel aspect %g\n", cam.width, cam.height, cam.pixel_aspect);
    std::printf("view layer %s\n", ss_scene_view_layer(scene.get()));
    return 0;
}

}  // namespace ss::cli
