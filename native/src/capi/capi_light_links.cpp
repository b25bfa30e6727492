// How the C API sets and reads a light's light and shadow linking.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <optional>
#include <string>
#include <vector>

#include "capi/capi_internal.h"

using namespace ss::capi;

namespace {

// count -1: every mesh (no set); 0..n: exactly the meshes listed.
std::optional<std::vector<int>> meshSetFrom(const int32_t* meshes, int32_t count, const char* parameter) {
    if (count == -1) return std::nullopt;
    if (count < 0)
        ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string("ss_scene_set_light_links: ") + parameter + " count " +
                                                std::to_string(count) + " is negative (-1 means every mesh)");
    if (count > 0) require(meshes, "ss_scene_set_light_links", parameter);
    return std::vector<int>(meshes, meshes + count);
}

void meshSetTo(const std::optional<std::vector<int>>& set, int32_t* out, int32_t capacity, int32_t* count,
               const char* parameter) {
    require(count, "ss_scene_get_light_links", parameter);
    *count = set ? int32_t(set->size()) : -1;
    if (!set || set->empty()) return;
    if (capacity < int32_t(set->size()))
        ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string("ss_scene_get_light_links: ") + parameter + " needs room for " +
                                                std::to_string(set->size()) + " indices, not " +
                                                std::to_string(capacity));
    require(out, "ss_scene_get_light_links", parameter);
    for (size_t i = 0; i < set->size(); ++i) out[i] = (*set)[i];
}

}  // namespace

extern "C" {

SS_API ss_status ss_scene_set_light_links(ss_scene* scene, int32_t light, const int32_t* blocker_meshes,
                                          int32_t blocker_count, const int32_t* receiver_meshes,
                                          int32_t receiver_count) {
    return guarded([&] {
        require(scene, "ss_scene_set_light_links", "scene");
        ss::LightLinks links;
        links.blockers = meshSetFrom(blocker_meshes, blocker_count, "blocker_meshes");
        links.receivers = meshSetFrom(receiver_meshes, receiver_count, "receiver_meshes");
        scene->scene.setLightLinks(light, std::move(links));
    });
}

SS_API ss_status ss_scene_get_light_links(const ss_scene* scene, int32_t light, int32_t* blocker_meshes,
                                          int32_t blocker_capacity, int32_t* blocker_count,
                                          int32_t* receiver_meshes, int32_t receiver_capacity,
                                          int32_t* receiver_count) {
    return guarded([&] {
        require(scene, "ss_scene_get_light_links", "scene");
        const ss::LightLinks& links = scene->scene.light(light, "ss_scene_get_light_links").links;
        meshSetTo(links.blockers, blocker_meshes, blocker_capacity, blocker_count, "blocker_count");
        meshSetTo(links.receivers, receiver_meshes, receiver_capacity, receiver_count, "receiver_count");
    });
}

}  // extern "C"
