// How the C API builds, loads, saves and describes scenes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstring>
#include <cmath>

#include "capi/capi_internal.h"
#include "io/scene_file.h"

using namespace ss::capi;

namespace {

glm::mat4 toMat4(const float m[16]) {
    glm::mat4 out;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) out[c][r] = m[c * 4 + r];
    return out;
}

void fromMat4(const glm::mat4& m, float out[16]) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) out[c * 4 + r] = m[c][r];
}

}  // namespace

extern "C" {

SS_API ss_status ss_scene_create(ss_scene** out) {
    return guarded([&] {
        require(out, "ss_scene_create", "out");
        *out = nullptr;
        *out = new ss_scene();
    });
}

SS_API void ss_scene_destroy(ss_scene* scene) {
    guarded([&] { delete scene; });
}

SS_API ss_status ss_scene_load(const char* path, ss_scene** out) {
    return guarded([&] {
        require(out, "ss_scene_load", "out");
        *out = nullptr;
        require(path, "ss_scene_load", "path");
        auto scene = std::make_unique<ss_scene>();
        scene->scene = ss::loadSceneFile(path);
        *out = scene.release();
    });
}

SS_API ss_status ss_scene_save(const ss_scene* scene, const char* path) {
    return guarded([&] {
        require(scene, "ss_scene_save", "scene");
        require(path, "ss_scene_save", "path");
        ss::saveSceneFile(scene->scene, path);
    });
}

}  // extern "C"

namespace {

ss::Mesh meshFrom(const char* function, const std::string& name, const float* xyz, uint32_t vertex_count,
                  const uint32_t* triangles, uint32_t triangle_count, uint32_t flags) {
    if (vertex_count > 0) require(xyz, function, "xyz");
    if (triangle_count > 0) require(triangles, function, "triangles");
    if (flags & ~uint32_t(SS_MESH_CAST | SS_MESH_RECEIVE | SS_MESH_THIN | SS_MESH_CAMERA_HIDDEN))
        ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string(function) + ": mesh '" + name +
                                                "' has unknown flag bits " + std::to_string(flags));
    ss::Mesh mesh;
    mesh.name = name;
    mesh.flags = flags;
    mesh.objectPositions.resize(vertex_count);
    for (uint32_t i = 0; i < vertex_count; ++i)
        mesh.objectPositions[i] = glm::vec3(xyz[3 * size_t(i)], xyz[3 * size_t(i) + 1], xyz[3 * size_t(i) + 2]);
    mesh.triangles.resize(triangle_count);
    for (uint32_t f = 0; f < triangle_count; ++f)
        mesh.triangles[f] = glm::uvec3(triangles[3 * size_t(f)], triangles[3 * size_t(f) + 1],
                                       triangles[3 * size_t(f) + 2]);
    return mesh;
}

ss::Light lightFrom(const char* function, const ss_light_desc* light) {
    require(light, function, "light");
    require(light->name, function, "light->name");
    ss::Light l;
    l.name = light->name;
    // The header's reserved values make every int32 a valid ss_light_type, so this check
    // sees whatever a C caller passed.
    const auto rawType = int32_t(light->type);
    if (rawType < int32_t(SS_LIGHT_DISK) || rawType > int32_t(SS_LIGHT_SUN))
        ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string(function) + ": light '" + l.name +
                                                "' has unknown type " + std::to_string(rawType));
    l.type = ss::LightType(rawType);  // the enums share their order
    l.lightToWorld = toMat4(light->light_to_world);
    l.size = light->size;
    l.sizeY = light->size_y;
    l.radius = light->radius;
    l.angle = light->angle;
    l.spotSize = light->spot_size;
    l.spotBlend = light->spot_blend;
    l.castShadows = light->cast_shadows != 0;
    return l;
}

}  // namespace

extern "C" {

SS_API ss_status ss_scene_add_mesh(ss_scene* scene, const char* name, const float* xyz,
                                   uint32_t vertex_count, const uint32_t* triangles,
                                   uint32_t triangle_count, const float object_to_world[16], uint32_t flags,
                                   int32_t* out_index) {
    return guarded([&] {
        require(scene, "ss_scene_add_mesh", "scene");
        require(name, "ss_scene_add_mesh", "name");
        ss::Mesh mesh = meshFrom("ss_scene_add_mesh", name, xyz, vertex_count, triangles, triangle_count, flags);
        if (object_to_world) mesh.objectToWorld = toMat4(object_to_world);
        int index = scene->scene.addMesh(std::move(mesh));
        if (out_index) *out_index = index;
    });
}

SS_API ss_status ss_scene_update_mesh(ss_scene* scene, int32_t index, const float* xyz,
                                      uint32_t vertex_count, const uint32_t* triangles,
                                      uint32_t triangle_count, uint32_t flags) {
    return guarded([&] {
        require(scene, "ss_scene_update_mesh", "scene");
        const auto& meshes = scene->scene.meshes();
        std::string name = index >= 0 && size_t(index) < meshes.size() ? meshes[size_t(index)].name : "";
        scene->scene.updateMesh(index, meshFrom("ss_scene_update_mesh", name, xyz, vertex_count, triangles,
                                                triangle_count, flags));
    });
}

SS_API ss_status ss_scene_set_mesh_transform(ss_scene* scene, int32_t index, const float object_to_world[16]) {
    return guarded([&] {
        require(scene, "ss_scene_set_mesh_transform", "scene");
        require(object_to_world, "ss_scene_set_mesh_transform", "object_to_world");
        scene->scene.setMeshTransform(index, toMat4(object_to_world));
    });
}

SS_API ss_status ss_scene_remove_mesh(ss_scene* scene, int32_t index) {
    return guarded([&] {
        require(scene, "ss_scene_remove_mesh", "scene");
        scene->scene.removeMesh(index);
    });
}

SS_API ss_status ss_scene_add_light(ss_scene* scene, const ss_light_desc* light, int32_t* out_index) {
    return guarded([&] {
        require(scene, "ss_scene_add_light", "scene");
        int index = scene->scene.addLight(lightFrom("ss_scene_add_light", light));
        if (out_index) *out_index = index;
    });
}

SS_API ss_status ss_scene_update_light(ss_scene* scene, int32_t index, const ss_light_desc* light) {
    return guarded([&] {
        require(scene, "ss_scene_update_light", "scene");
        scene->scene.updateLight(index, lightFrom("ss_scene_update_light", light));
    });
}

SS_API ss_status ss_scene_remove_light(ss_scene* scene, int32_t index) {
    return guarded([&] {
        require(scene, "ss_scene_remove_light", "scene");
        scene->scene.removeLight(index);
    });
}

SS_API ss_status ss_scene_set_camera(ss_scene* scene, const ss_camera_desc* camera) {
    return guarded([&] {
        require(scene, "ss_scene_set_camera", "scene");
        require(camera, "ss_scene_set_camera", "camera");
        ss::Camera c;
        c.worldToCamera = toMat4(camera->world_to_camera);
        c.projection = toMat4(camera->projection);
        c.width = camera->width;
        c.height = camera->height;
        c.pixelAspect = camera->pixel_aspect;
        if (!std::isfinite(c.pixelAspect) || !(c.pixelAspect > 0.0f))
            ss::fail(SS_ERROR_INVALID_SCENE, "camera pixel_aspect must be a number greater than zero");
        scene->scene.setCamera(c);
    });
}

SS_API ss_status ss_scene_get_camera(const ss_scene* scene, ss_camera_desc* out) {
    return guarded([&] {
        require(scene, "ss_scene_get_camera", "scene");
        require(out, "ss_scene_get_camera", "out");
        const ss::Camera& c = scene->scene.camera();
        fromMat4(c.worldToCamera, out->world_to_camera);
        fromMat4(c.projection, out->projection);
        out->width = c.width;
        out->height = c.height;
        out->pixel_aspect = c.pixelAspect;
    });
}

SS_API ss_status ss_scene_set_view_layer(ss_scene* scene, const char* name) {
    return guarded([&] {
        require(scene, "ss_scene_set_view_layer", "scene");
        require(name, "ss_scene_set_view_layer", "name");
        scene->scene.setViewLayer(name);
    });
}

SS_API int32_t ss_scene_light_count(const ss_scene* scene) {
    return scene ? int32_t(scene->scene.lights().size()) : 0;
}

SS_API const char* ss_scene_light_name(const ss_scene* scene, int32_t index) {
    const char* name = nullptr;
    guarded([&] {
        require(scene, "ss_scene_light_name", "scene");
        name = scene->scene.light(index, "ss_scene_light_name").name.c_str();
    });
    return name;
}

SS_API int32_t ss_scene_mesh_count(const ss_scene* scene) {
    return scene ? int32_t(scene->scene.meshes().size()) : 0;
}

SS_API ss_status ss_scene_mesh_report(const ss_scene* scene, int32_t mesh, char* buffer,
                                      size_t buffer_size) {
    return guarded([&] {
        require(scene, "ss_scene_mesh_report", "scene");
        const ss::Mesh& m = scene->scene.mesh(mesh, "ss_scene_mesh_report");
        copyOut(m.report.toJson(m.name), buffer, buffer_size, "ss_scene_mesh_report");
    });
}

}  // extern "C"

extern "C" {

SS_API ss_status ss_scene_get_light(const ss_scene* scene, int32_t index, ss_light_desc* out) {
    return guarded([&] {
        require(scene, "ss_scene_get_light", "scene");
        require(out, "ss_scene_get_light", "out");
        const ss::Light& l = scene->scene.light(index, "ss_scene_get_light");
        out->name = l.name.c_str();
        out->type = ss_light_type(int(l.type));
        fromMat4(l.lightToWorld, out->light_to_world);
        out->size = l.size;
        out->size_y = l.sizeY;
        out->radius = l.radius;
        out->angle = l.angle;
        out->spot_size = l.spotSize;
        out->spot_blend = l.spotBlend;
        out->cast_shadows = l.castShadows ? 1 : 0;
    });
}

SS_API const char* ss_scene_view_layer(const ss_scene* scene) {
    return scene ? scene->scene.viewLayer().c_str() : nullptr;
}

}  // extern "C"
