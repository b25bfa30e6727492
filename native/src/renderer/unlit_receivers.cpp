// How the pixels of meshes a light does not light are taken out of its layers.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "renderer/unlit_receivers.h"

#include <vector>

#include "core/error.h"

namespace ss {

void maskUnlitReceivers(const Scene& scene, int lightIndex, const CameraImages& camera, Layers& layers) {
    if (!scene.light(lightIndex).links.receivers) return;
    Image *visibility = nullptr, *mask = nullptr;
    for (auto& [name, image] : layers.items) {
        if (name == "V") visibility = &image;
        if (name == "mask") mask = &image;
    }
    if (!visibility || !mask || visibility->width != camera.width || visibility->height != camera.height)
        fail(SS_ERROR_INTERNAL, "light links: the layers do not match the camera pass");
    std::vector<char> lit(scene.meshes().size());
    for (size_t i = 0; i < lit.size(); ++i) lit[i] = scene.receivesFrom(int(i), lightIndex);
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const int mesh = int(camera.ids[camera.index(x, y)].x);
            if (mesh < 0 || size_t(mesh) >= lit.size() || lit[size_t(mesh)]) continue;
            visibility->at(x, y) = 1.0f;
            mask->at(x, y) = 0.0f;
        }
}

}  // namespace ss
