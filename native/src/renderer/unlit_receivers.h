// Where a light-linked light sends no light: the pixels of meshes outside its receivers.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "core/image.h"
#include "core/scene.h"
#include "scene_cache/scene_cache.h"

namespace ss {

// Light linking (LightLinks::receivers) for the GL methods, which shade the shared camera pass
// of every receiving mesh: each pixel whose mesh the light does not light leaves the mask with
// V = 1, what the contract gives where a light does not reach (the render there owes nothing
// to this light). A light without receiver links leaves the layers as they are.
void maskUnlitReceivers(const Scene& scene, int lightIndex, const CameraImages& camera, Layers& layers);

}  // namespace ss
