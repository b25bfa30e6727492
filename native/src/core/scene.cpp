// How meshes, lights and the camera enter a scene.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/scene.h"

#include <atomic>

#include "core/error.h"
#include "core/names.h"

namespace ss {

namespace {

// Refuses a name another light has, or one that writes the same EXR passes (found here, before
// anything renders, not when the file is written). `self`: the index being replaced, or -1.
void checkLightNameFree(const std::vector<Light>& lights, const std::string& name, int self) {
    const std::string token = passToken(name);
    for (size_t i = 0; i < lights.size(); ++i) {
        if (int(i) == self) continue;
        if (lights[i].name == name) fail(SS_ERROR_INVALID_SCENE, "two lights are named " + quoted(name));
        if (passToken(lights[i].name) == token)
            fail(SS_ERROR_INVALID_SCENE, "lights " + quoted(lights[i].name) + " and " + quoted(name) +
                                             " would write the same passes ('" + token +
                                             "_<method>': pass names make dots and spaces '_'): rename one");
    }
}

}  // namespace

uint64_t Scene::nextId() {
    static std::atomic<uint64_t> counter{1};
    return counter++;
}

uint64_t Scene::nextVersion() {
    static std::atomic<uint64_t> counter{1};
    return counter++;
}

int Scene::addMesh(Mesh mesh) {
    checkName("mesh", mesh.name);
    mesh.finalize();
    if (mesh.alpha) {
        mesh.alpha->validate(mesh.name, mesh.triangles.size());
        if (mesh.alpha->opaque()) mesh.alpha = nullptr;
    }
    mesh.version = nextVersion();
    mesh.shapeVersion = mesh.version;
    meshes_.push_back(std::move(mesh));
    geometryVersion_ = nextVersion();
    ++revision_;
    return int(meshes_.size()) - 1;
}

const Mesh& Scene::mesh(int index, const std::string& where) const {
    return meshes_[checkedIndex(index, meshes_.size(), where, "mesh", "meshes", "scene")];
}

void Scene::updateMesh(int index, Mesh mesh) {
    const Mesh& old = this->mesh(index, "updating a mesh");
    mesh.name = old.name;
    mesh.objectToWorld = old.objectToWorld;
    mesh.finalize();
    mesh.version = nextVersion();
    mesh.shapeVersion = mesh.version;
    meshes_[size_t(index)] = std::move(mesh);
    geometryVersion_ = nextVersion();
    ++revision_;
}

void Scene::setMeshTransform(int index, const glm::mat4& objectToWorld) {
    (void)this->mesh(index, "moving a mesh");
    Mesh& mesh = meshes_[size_t(index)];
    mesh.place(objectToWorld);
    mesh.version = nextVersion();
    geometryVersion_ = nextVersion();
    ++revision_;
}

void Scene::setMeshAlpha(int index, MeshAlpha alpha) {
    const Mesh& old = this->mesh(index, "setting a mesh's materials");
    alpha.validate(old.name, old.triangles.size());
    Mesh& mesh = meshes_[size_t(index)];
    mesh.alpha = alpha.opaque() ? nullptr : std::make_shared<const MeshAlpha>(std::move(alpha));
    mesh.version = nextVersion();
    mesh.shapeVersion = mesh.version;
    geometryVersion_ = nextVersion();
    ++revision_;
}

void Scene::removeMesh(int index) {
    (void)mesh(index, "removing a mesh");
    meshes_.erase(meshes_.begin() + index);
    for (Light& light : lights_)
        if (light.links.linked()) {
            light.links.meshRemoved(index);
            light.version = nextVersion();
        }
    geometryVersion_ = nextVersion();
    ++revision_;
}

void Scene::updateLight(int index, Light light) {
    (void)this->light(index);  // throws for an index out of range
    checkName("light", light.name);
    checkLightNameFree(lights_, light.name, index);
    light.validate();
    light.links = lights_[size_t(index)].links;
    light.version = nextVersion();
    lights_[size_t(index)] = std::move(light);
    ++revision_;
}

void Scene::removeLight(int index) {
    (void)light(index);
    lights_.erase(lights_.begin() + index);
    ++revision_;
}

void Scene::setLightLinks(int index, LightLinks links) {
    (void)this->light(index, "setting light links");
    if (links.receivers) links.receivers = linkedMeshSet(std::move(*links.receivers), meshes_.size(), "receiver");
    if (links.blockers) links.blockers = linkedMeshSet(std::move(*links.blockers), meshes_.size(), "blocker");
    Light& light = lights_[size_t(index)];
    if (light.links == links) return;
    light.links = std::move(links);
    light.version = nextVersion();
    ++revision_;
}

bool Scene::castsFor(int mesh, int light) const {
    return meshes_[size_t(mesh)].casts() && lights_[size_t(light)].links.blockedBy(mesh);
}

bool Scene::receivesFrom(int mesh, int light) const {
    return meshes_[size_t(mesh)].receives() && lights_[size_t(light)].links.lights(mesh);
}

int Scene::addLight(Light light) {
    checkName("light", light.name);
    checkLightNameFree(lights_, light.name, -1);
    light.validate();
    LightLinks& links = light.links;
    if (links.receivers) links.receivers = linkedMeshSet(std::move(*links.receivers), meshes_.size(), "receiver");
    if (links.blockers) links.blockers = linkedMeshSet(std::move(*links.blockers), meshes_.size(), "blocker");
    light.version = nextVersion();
    lights_.push_back(std::move(light));
    ++revision_;
    return int(lights_.size()) - 1;
}

void Scene::setCamera(const Camera& camera) {
    camera.validate();
    camera_ = camera;
    cameraVersion_ = nextVersion();
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

const Light& Scene::light(int index, const std::string& where) const {
    return lights_[checkedIndex(index, lights_.size(), where, "light", "lights", "scene")];
}

Scene::LightGeometryKey Scene::lightGeometryKey(int lightIndex) const {
    return {id(), geometryVersion_, light(lightIndex, "lightGeometryKey").version, lightIndex};
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
