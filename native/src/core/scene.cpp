// How meshes, lights and the camera enter a scene.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/scene.h"

#include <atomic>

#include "core/error.h"
#include "core/names.h"

namespace ss {

uint64_t Scene::nextId() {
    static std::atomic<uint64_t> counter{1};
    return counter++;
}

int Scene::addMesh(Mesh mesh) {
    checkName("mesh", mesh.name);
    mesh.finalize();
    meshes_.push_back(std::move(mesh));
    ++revision_;
    return int(meshes_.size()) - 1;
}

int Scene::addLight(Light light) {
    checkName("light", light.name);
    if (findLight(light.name) >= 0)
        fail(SS_ERROR_INVALID_SCENE, "two lights are named " + quoted(light.name));
    light.validate();
    lights_.push_back(std::move(light));
    ++revision_;
    return int(lights_.size()) - 1;
}

void Scene::setCamera(const Camera& camera) {
    camera.validate();
    camera_ = camera;
    ++revision_;
}

void Scene::setViewLayer(const std::string& name) {
    checkViewLayerName(name);
    viewLayer_ = name;
    ++revision_;
}

const Camera& Scene::camera() const {
    if (!camera_) fail(SS_ERROR_INVALID_SCENE, "the scene has no camera");
    return *camera_;
}

const Light& Scene::light(int index) const {
    if (index < 0 || size_t(index) >= lights_.size())
        fail(SS_ERROR_INVALID_ARGUMENT, "light index " + std::to_string(index) + " is out of range (the scene has " +
                                            std::to_string(lights_.size()) + " lights)");
    return lights_[size_t(index)];
}

int Scene::findLight(const std::string& name) const {
    for (size_t i = 0; i < lights_.size(); ++i)
        if (lights_[i].name == name) return int(i);
    return -1;
}

Bounds Scene::bounds() const {
    Bounds b;
    for (const Mesh& m : meshes_)
        for (const glm::vec3& p : m.positions) b.extend(p);
    return b;
}

}  // namespace ss
