// How the sweep's per-mesh projections are looked up by mesh version, made sample by sample when
// missing, and kept within the cache's budget.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/projection_cache.h"

#include <unordered_set>

namespace ss {

namespace {

bool samePlane(const ReceiverPlane& a, const ReceiverPlane& b) {
    return a.origin == b.origin && a.normal == b.normal && a.u == b.u && a.v == b.v && a.cu == b.cu && a.cv == b.cv &&
           a.half == b.half;
}

bool sameSamples(const std::vector<LightSample>& a, const std::vector<LightSample>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].point != b[i].point || a[i].toLight != b[i].toLight || a[i].directional != b[i].directional)
            return false;
    return true;
}

size_t edgeBytes(const std::vector<planar::DirectedEdge>& edges) {
    return edges.capacity() * sizeof(planar::DirectedEdge);
}

}  // namespace

size_t MeshProjection::bytes() const {
    size_t n = sizeof(MeshProjection) + edges.capacity() * sizeof(edges[0]);
    for (const auto& e : edges) n += edgeBytes(e);
    return n;
}

void SweepProjectionCache::drop(Set& set) {
    for (const auto& [version, p] : set.meshes) held_ -= p->bytes();
    set.meshes.clear();
    held_ -= set.weightedBytes;
    set.weighted.clear();
    set.weightedBytes = 0;
    held_ -= set.partsBytes;
    set.parts.clear();
    set.partsBytes = 0;
}

SweepProjectionCache::Pass SweepProjectionCache::begin(int lightIndex, int cluster, const Scene& scene,
                                                       const std::vector<int>& occluders, const ReceiverPlane& plane,
                                                       const planar::Snap& snap,
                                                       const std::vector<LightSample>& samples) {
    Set& set = sets_[{lightIndex, cluster}];
    if (!samePlane(set.plane, plane) || !sameSamples(set.samples, samples)) {
        drop(set);
        set.plane = plane;
        set.samples = samples;
    }
    // Meshes no longer among the occluders (removed, edited, moved) go first, so that what
    // replaces them has their room in the budget.
    std::unordered_set<uint64_t> current;
    for (int mi : occluders) current.insert(scene.meshes()[mi].version);
    for (auto it = set.meshes.begin(); it != set.meshes.end();) {
        if (current.count(it->first)) {
            ++it;
        } else {
            held_ -= it->second->bytes();
            it = set.meshes.erase(it);
        }
    }
    return Pass(*this, scene, occluders, plane, snap, samples, {lightIndex, cluster});
}

SweepProjectionCache::Pass::Pass(SweepProjectionCache& cache, const Scene& scene, const std::vector<int>& occluders,
                                 const ReceiverPlane& plane, const planar::Snap& snap,
                                 const std::vector<LightSample>& samples, std::pair<int, int> set)
    : cache_(cache), scene_(scene), occluders_(occluders), plane_(plane), snap_(snap), samples_(samples), set_(set),
      cached_(occluders.size()), making_(occluders.size()), stats_(occluders.size()) {
    const Set& s = cache_.sets_.at(set_);
    for (size_t i = 0; i < occluders_.size(); ++i) {
        auto found = s.meshes.find(scene_.meshes()[occluders_[i]].version);
        if (found != s.meshes.end()) {
            cached_[i] = found->second;
            stats_[i] = found->second->stats;
            ++reused_;
        } else if (cache_.budget_ > 0) {
            making_[i] = std::make_unique<MeshProjection>();
            making_[i]->edges.resize(samples_.size());
            pendingBytes_ += making_[i]->bytes();
        }
    }
}

void SweepProjectionCache::Pass::append(size_t s, std::vector<planar::DirectedEdge>* out) {
    for (size_t i = 0; i < occluders_.size(); ++i) {
        if (cached_[i]) {
            const std::vector<planar::DirectedEdge>& e = cached_[i]->edges[s];
            out->insert(out->end(), e.begin(), e.end());
            continue;
        }
        const Mesh& mesh = scene_.meshes()[occluders_[i]];
        if (!making_[i]) {
            projectMeshSample(mesh, plane_, snap_, samples_[s], out, &stats_[i]);
            continue;
        }
        std::vector<planar::DirectedEdge>& kept = making_[i]->edges[s];
        projectMeshSample(mesh, plane_, snap_, samples_[s], &kept, &stats_[i]);
        kept.shrink_to_fit();
        out->insert(out->end(), kept.begin(), kept.end());
        pendingBytes_ += edgeBytes(kept);
        if (cache_.held_ + pendingBytes_ > cache_.budget_) {
            // No room to keep it: projected sample by sample from here on, like an uncached mesh.
            pendingBytes_ -= making_[i]->bytes();
            making_[i].reset();
        }
    }
}

void SweepProjectionCache::Pass::finish(ProjectionStats* stats) {
    Set& set = cache_.sets_.at(set_);
    for (size_t i = 0; i < occluders_.size(); ++i) {
        if (making_[i]) {
            making_[i]->stats = stats_[i];
            auto [it, added] = set.meshes.try_emplace(scene_.meshes()[occluders_[i]].version);
            if (added) {
                cache_.held_ += making_[i]->bytes();
                it->second = std::move(making_[i]);
            }
        }
        stats->silhouetteEdges += stats_[i].silhouetteEdges;
        stats->fallbackTriangles += stats_[i].fallbackTriangles;
    }
    pendingBytes_ = 0;
    stats->meshesReused += reused_;
    stats->meshesProjected += int(occluders_.size()) - reused_;
}

WeightedTriangles* SweepProjectionCache::Pass::weighted() {
    return cache_.budget_ > 0 ? &cache_.sets_.at(set_).weighted : nullptr;
}

void SweepProjectionCache::Pass::weighed() {
    Set& set = cache_.sets_.at(set_);
    cache_.recount(set.weighted, set.weightedBytes);
}

FilledParts* SweepProjectionCache::Pass::filledParts() {
    return cache_.budget_ > 0 ? &cache_.sets_.at(set_).parts : nullptr;
}

void SweepProjectionCache::Pass::filled() {
    Set& set = cache_.sets_.at(set_);
    cache_.recount(set.parts, set.partsBytes);
}

void SweepProjectionCache::keep(int lights, int lightIndex, int clusters) {
    for (auto it = sets_.begin(); it != sets_.end();) {
        const auto [light, cluster] = it->first;
        if (light >= lights || (light == lightIndex && cluster >= clusters)) {
            drop(it->second);
            it = sets_.erase(it);
        } else {
            ++it;
        }
    }
}

}  // namespace ss
