// How one cold frame of a method is timed stage by stage (shared passes, prepare, render, readback).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <map>
#include <string>

#include "core/image.h"
#include "core/scene.h"

namespace ss::bench {

struct Stages {
    double meshUpload = 0, cameraPass = 0, shadowMap = 0, prepare = 0, render = 0, readback = 0;
    double total() const { return meshUpload + cameraPass + shadowMap + prepare + render; }
};

// Light 0 of `scene` with `method` (its settings in `options`; `samples` the render's sample
// count, 0 = the method's default) on a fresh SceneCache (every shared pass drawn again), on one
// long-lived render thread; `keep` receives the layers. Throws what the method throws, and
// ss::Error(SS_ERROR_CANCELLED) when the method reports progress after `budgetSeconds` (0: none).
Stages runOnce(const Scene& scene, const std::string& method, Layers* keep = nullptr,
               double budgetSeconds = 0.0, const std::map<std::string, std::string>& options = {},
               int samples = 0);

}  // namespace ss::bench
