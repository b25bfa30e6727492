// Which Embree scene to reuse: one TraceScene kept per (scene id, revision), rebuilt on change.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <memory>
#include <mutex>

#include "reference/trace_scene.h"

namespace ss {

// Holds the most recent TraceScene. A render keeps its shared_ptr alive, so a rebuild for a
// newer revision never pulls the scene out from under a render still running.
class TraceSceneCache {
public:
    std::shared_ptr<const TraceScene> get(const Scene& scene);
    int builds() const { return builds_; }  // how many TraceScenes were built (for tests)

private:
    std::mutex mutex_;
    std::shared_ptr<const TraceScene> current_;
    int builds_ = 0;
};

}  // namespace ss
