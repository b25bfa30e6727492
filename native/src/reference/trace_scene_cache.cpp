// How the per-(scene id, geometry version) TraceScene cache decides to rebuild, and what it keeps.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/trace_scene_cache.h"

#include <unordered_set>

#include "reference/mesh_bvh.h"

namespace ss {
namespace {

bool shows(const TraceScene& trace, const Scene& scene) {
    return trace.sceneId() == scene.id() && trace.geometryVersion() == scene.geometryVersion();
}

}  // namespace

std::shared_ptr<const TraceScene> TraceSceneCache::get(const Scene& scene, int lightIndex) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::shared_ptr<const TraceScene> all = currentLocked(scene);
    if (lightIndex < 0) return all;
    const std::optional<std::vector<int>>& blockers = scene.light(lightIndex, "TraceSceneCache").links.blockers;
    if (!blockers) return all;
    for (const auto& trace : linked_)
        if (trace->blockers() == blockers) return trace;
    // A few blocker sets are kept: a scene rarely has more linked lights than that.
    constexpr size_t kLinkedKept = 8;
    if (linked_.size() >= kLinkedKept) linked_.erase(linked_.begin());
    linked_.push_back(std::make_shared<const TraceScene>(scene, all->meshBvhs(), lightIndex));
    ++builds_;
    meshBvhBuilds_ += linked_.back()->meshBvhBuilds();
    return linked_.back();
}

std::shared_ptr<const TraceScene> TraceSceneCache::currentLocked(const Scene& scene) {
    if (!current_ || !shows(*current_, scene)) {
        linked_.clear();
        // The meshes whose shape stayed keep their BVHs; the others' go with the old scene.
        if (current_) kept_ = current_->meshBvhs();
        current_.reset();
        current_ = std::make_shared<const TraceScene>(scene, kept_);
        kept_.clear();
        ++builds_;
        meshBvhBuilds_ += current_->meshBvhBuilds();
    }
    return current_;
}

void TraceSceneCache::dropStale(const Scene& scene) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!current_ || shows(*current_, scene)) return;
    // Only the BVHs of meshes that kept their shape stay for the next build.
    std::unordered_set<uint64_t> shapes;
    for (const Mesh& mesh : scene.meshes()) shapes.insert(MeshBvh::keyOf(mesh).packed());
    kept_.clear();
    for (const auto& bvh : current_->meshBvhs())
        if (shapes.count(bvh->key().packed())) kept_.push_back(bvh);
    current_.reset();
    linked_.clear();
}

int TraceSceneCache::builds() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return builds_;
}

int TraceSceneCache::meshBvhBuilds() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return meshBvhBuilds_;
}

}  // namespace ss
