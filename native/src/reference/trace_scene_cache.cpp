// How the per-(scene id, revision) TraceScene cache decides to rebuild.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/trace_scene_cache.h"

namespace ss {

std::shared_ptr<const TraceScene> TraceSceneCache::get(const Scene& scene) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!current_ || current_->sceneId() != scene.id() || current_->revision() != scene.revision()) {
        current_.reset();  // free the old BVH before building the new one
        current_ = std::make_shared<const TraceScene>(scene);
        ++builds_;
    }
    return current_;
}

}  // namespace ss
