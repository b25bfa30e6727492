// Which Embree scene to reuse: one TraceScene kept per (scene id, geometry version), rebuilt on
// change, and one per shadow-linked blocker set beside it.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <memory>
#include <mutex>
#include <vector>

#include "reference/trace_scene.h"

namespace ss {

// Holds the most recent TraceScene. A render keeps its shared_ptr alive, so a rebuild for newer
// geometry never pulls the scene out from under a render still running. Keyed by the geometry
// version, not the revision: a light or camera edit keeps the BVH. A rebuild keeps each mesh's
// BVH whose shape is unchanged (a moved object costs its instance, not its BVH).
class TraceSceneCache {
public:
    // With `lightIndex`, the TraceScene whose shadow rays see that light's blockers: the
    // unlinked one for a light without shadow linking, else one per blocker set, sharing the
    // unlinked one's mesh BVHs (its build costs the instances only).
    std::shared_ptr<const TraceScene> get(const Scene& scene, int lightIndex = -1);
    // Lets go of a TraceScene that no longer shows `scene`'s geometry (its memory is the BVH's),
    // keeping the BVHs of the meshes `scene` still has in the same shape.
    void dropStale(const Scene& scene);
    int builds() const;         // how many TraceScenes were built
    int meshBvhBuilds() const;  // how many mesh BVHs they built

private:
    mutable std::mutex mutex_;
    std::shared_ptr<const TraceScene> current_;
    std::vector<std::shared_ptr<const TraceScene>> linked_;  // of current_'s geometry, by blocker set
    std::shared_ptr<const TraceScene> currentLocked(const Scene& scene);
    std::vector<std::shared_ptr<const MeshBvh>> kept_;  // for the next build
    int builds_ = 0;
    int meshBvhBuilds_ = 0;
};

}  // namespace ss
