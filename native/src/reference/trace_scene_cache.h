// Which Embree scene to reuse: one TraceScene kept per (scene id, geometry version), rebuilt on change.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <memory>
#include <mutex>

#include "reference/trace_scene.h"

namespace ss {

// Holds the most recent TraceScene. A render keeps its shared_ptr alive, so a rebuild for newer
// geometry never pulls the scene out from under a render still running. Keyed by the geometry
// version, not the revision: a light or camera edit keeps the BVH.
class TraceSceneCache {
public:
    std::shared_ptr<const TraceScene> get(const Scene& scene);
    // Lets go of a TraceScene that no longer shows `scene`'s geometry (its memory is the BVH's).
    void dropStale(const Scene& scene);
    int builds() const;  // how many TraceScenes were built

private:
    mutable std::mutex mutex_;
    std::shared_ptr<const TraceScene> current_;
    int builds_ = 0;
};

}  // namespace ss
