// How the meshes beyond the scene range are found once per geometry and camera, and left out.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "renderer/scene_in_range.h"

#include "core/error.h"
#include "core/scene_range.h"

namespace ss {

namespace {
// As many as the renderer keeps frames for (the add-on's two previews and its final render).
constexpr size_t kKeptEntries = 3;
}  // namespace

const Scene& ScenesInRange::forRender(const Scene& scene, int lightIndex, std::vector<std::string>* warnings) {
    const SceneRange range = sceneRangeOf(scene.camera());
    if (std::optional<std::string> why = lightOutOfRange(scene.light(lightIndex), range))
        fail(SS_ERROR_INVALID_SCENE, *why + ": it gets no pass");
    Entry* entry = nullptr;
    for (Entry& e : entries_)
        if (e.sceneId == scene.id()) entry = &e;
    if (!entry || entry->geometryVersion != scene.geometryVersion() || entry->cameraVersion != scene.cameraVersion()) {
        Entry fresh;
        fresh.sceneId = scene.id();
        fresh.geometryVersion = scene.geometryVersion();
        fresh.cameraVersion = scene.cameraVersion();
        for (size_t i = 0; i < scene.meshes().size(); ++i)
            if (std::optional<std::string> why = meshOutOfRange(scene.meshes()[i], range)) {
                fresh.warnings.push_back(*why);
                fresh.skipped.push_back(int(i));
            }
        if (entry) {
            *entry = std::move(fresh);
        } else {
            if (entries_.size() >= kKeptEntries) entries_.erase(entries_.begin());
            entries_.push_back(std::move(fresh));
            entry = &entries_.back();
        }
    }
    if (warnings) warnings->insert(warnings->end(), entry->warnings.begin(), entry->warnings.end());
    if (entry->skipped.empty()) return scene;
    if (!entry->copy || entry->revision != scene.revision()) {
        auto copy = std::make_unique<Scene>(scene);
        for (auto it = entry->skipped.rbegin(); it != entry->skipped.rend(); ++it) copy->removeMesh(*it);
        entry->copy = std::move(copy);
        entry->revision = scene.revision();
    }
    return *entry->copy;
}

}  // namespace ss
