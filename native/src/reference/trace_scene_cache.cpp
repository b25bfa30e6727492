// How the per-(scene id, geometry version) TraceScene cache decides to rebuild.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/trace_scene_cache.h"

namespace ss {
namespace {

bool shows(const TraceScene& trace, const Scene& scene) {
    return trace.sceneId() == scene.id() && trace.geometryVersion() == scene.geometryVersion();
}

}  // namespace

std::shared_ptr<const TraceScene> TraceSceneCache::get(const Scene& scene) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!current_ || !shows(*current_, scene)) {
        current_.reset();  // free the old BVH before building the new one
        current_ = std::make_shared<const TraceScene>(scene);
        ++builds_;
    }
    return current_;
}

void TraceSceneCache::dropStale(const Scene& scene) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (current_ && !shows(*current_, scene)) current_.reset();
}

int TraceSceneCache::builds() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return builds_;
}

}  // namespace ss
