// How the sweep shadow mesh becomes the camera's V and mask with GL: drawn with the camera's own
// matrices and pixel centres, then resolved over the camera pass so occluders in front hide it.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "methods/method.h"
#include "methods/sweep/shadow.h"
#include "scene_cache/scene_cache.h"

namespace ss {

// Layers "V" and "mask" per camera pixel (row 0 = top): mask where the camera sees the receiver
// plane's mesh and the light reaches it (the visibility contract), V = 1 - the shadow intensity
// there. Only these two channels are read back: the camera pass stays on the GPU. Must run on
// the render thread.
Layers drawSweepShadow(SceneCache& sceneCache, const SweepShadow& shadow, int lightIndex);

}  // namespace ss
