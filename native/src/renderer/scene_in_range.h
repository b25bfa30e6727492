// Which scene a render works on: the scene itself, or, when meshes lie beyond the scene range
// (core/scene_range.h), a copy without them, kept while the scene does not change.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/scene.h"

namespace ss {

class ScenesInRange {
public:
    // The scene to render light `lightIndex` of `scene` with, and in *warnings one message per
    // skipped mesh, naming it. Throws ss::Error(SS_ERROR_INVALID_SCENE) naming the light when
    // it is beyond the range, or the camera when it is. The copy's lights are the scene's, at
    // the same indices; it lives until the scene changes or is among the oldest kept.
    const Scene& forRender(const Scene& scene, int lightIndex, std::vector<std::string>* warnings);

private:
    struct Entry {
        uint64_t sceneId = 0, geometryVersion = 0, cameraVersion = 0, revision = 0;
        std::vector<std::string> warnings;  // one per skipped mesh
        std::vector<int> skipped;           // their indices, ascending
        std::unique_ptr<Scene> copy;        // of `revision`, without them; null while none is
    };
    std::vector<Entry> entries_;  // the scenes rendered last, least recent first
};

}  // namespace ss
