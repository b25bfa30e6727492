// Which shadow edges each occluder casts for each light sample, kept per mesh across renders so
// that after an edit only the moved or edited meshes are projected again; the filled parts and
// the weighted triangles of the last shadow, so that only the parts and triangles near what
// changed are filled and weighed again.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/scene.h"
#include "methods/sweep/filled_parts.h"
#include "methods/sweep/projection.h"
#include "methods/sweep/receiver.h"
#include "methods/sweep/weights.h"
#include "planar/snap.h"
#include "sampling/light_samples.h"

namespace ss {

// One occluder's shadow edges for each sample that casts onto the plane (in the samples' order).
struct MeshProjection {
    std::vector<std::vector<planar::DirectedEdge>> edges;
    ProjectionStats stats;  // silhouetteEdges and fallbackTriangles of this mesh
    size_t bytes() const;
};

// The projections of the occluders of the last shadow computed per (light index, cluster): a
// mesh is projected again only when its Mesh::version (a move or an edit), the receiver plane or
// the samples changed. The same set holds the last shadow's filled parts (filled_parts.h) and
// weighted triangles (weights.h), which the next shadow of the same plane and samples reuses
// where its outlines did not change. A set
// keeps only the occluders of its last shadow, so a removed, moved or edited mesh's projections
// go with the next shadow of that light; keep() drops the sets of lights and clusters the caller
// no longer has. What is held stays within a byte budget: a mesh that does not fit is projected
// sample by sample for the shadow at hand and not kept (as with a budget of 0, which keeps
// nothing). Not thread-safe (one per method object).
class SweepProjectionCache {
public:
    // Silhouette edges are a few thousand per sample for a 100k-triangle closed mesh (about
    // 1 MiB over 16 samples); meshes projected face by face (open ones) hold far more, and those
    // the budget sheds. A shadow of 300k triangles (nine such meshes) keeps about 30 MiB of
    // filled parts and 30 MiB of weighted triangles.
    static constexpr size_t kDefaultBudget = size_t(128) << 20;
    explicit SweepProjectionCache(size_t budgetBytes = kDefaultBudget) : budget_(budgetBytes) {}

    // One shadow's projections: every occluder's edges, sample by sample.
    class Pass {
    public:
        // Appends the edges of every occluder for casting sample `s`, in the occluders' order:
        // taken from the cache, or projected now.
        void append(size_t s, std::vector<planar::DirectedEdge>* out);
        // After the last sample: the meshes projected whole are kept (within the budget), and
        // the projection stats (meshes projected and reused, edges, fallback triangles) added to
        // *stats. A pass abandoned before (cancelled) keeps nothing new.
        void finish(ProjectionStats* stats);
        // The weighted triangles of this set's last shadow, to pass to weighShadowMesh (null when
        // the budget is 0); weighed() after that call keeps the new ones within the budget.
        WeightedTriangles* weighted();
        void weighed();
        // The same for the filled parts (fillShadowParts) and filled() after that call.
        FilledParts* filledParts();
        void filled();

    private:
        friend class SweepProjectionCache;
        Pass(SweepProjectionCache& cache, const Scene& scene, const std::vector<int>& occluders,
             const ReceiverPlane& plane, const planar::Snap& snap, const std::vector<LightSample>& samples,
             std::pair<int, int> set);
        SweepProjectionCache& cache_;
        const Scene& scene_;
        const std::vector<int>& occluders_;
        const ReceiverPlane& plane_;
        const planar::Snap& snap_;
        const std::vector<LightSample>& samples_;
        std::pair<int, int> set_;
        // Per occluder: its cached projection, or the one being made (null once it outgrew the
        // room left in the budget), and its stats.
        std::vector<std::shared_ptr<const MeshProjection>> cached_;
        std::vector<std::unique_ptr<MeshProjection>> making_;
        std::vector<ProjectionStats> stats_;
        size_t pendingBytes_ = 0;
        int reused_ = 0;
    };

    // `samples`: those of the cluster that cast onto `plane`. The references must outlive the pass.
    Pass begin(int lightIndex, int cluster, const Scene& scene, const std::vector<int>& occluders,
               const ReceiverPlane& plane, const planar::Snap& snap, const std::vector<LightSample>& samples);
    // Drops the sets of lights at index `lights` and beyond, and those of light `lightIndex`'s
    // clusters at `clusters` and beyond.
    void keep(int lights, int lightIndex, int clusters);
    size_t bytes() const { return held_; }
    size_t weightedBytes() const {  // the part of bytes() the weighted triangles hold
        size_t b = 0;
        for (const auto& [key, set] : sets_) b += set.weightedBytes;
        return b;
    }
    size_t filledBytes() const {  // the part of bytes() the filled parts hold
        size_t b = 0;
        for (const auto& [key, set] : sets_) b += set.partsBytes;
        return b;
    }

private:
    struct Set {
        ReceiverPlane plane;
        std::vector<LightSample> samples;
        std::unordered_map<uint64_t, std::shared_ptr<const MeshProjection>> meshes;  // by Mesh::version
        WeightedTriangles weighted;
        size_t weightedBytes = 0;  // counted in held_
        FilledParts parts;
        size_t partsBytes = 0;  // counted in held_
    };
    void drop(Set& set);
    // Counts what `kept` holds now in place of the `counted` bytes it held, or clears it when
    // that does not fit the budget.
    template <class Kept>
    void recount(Kept& kept, size_t& counted) {
        held_ -= counted;
        counted = kept.bytes();
        if (held_ + counted > budget_) {
            kept.clear();
            counted = 0;
        }
        held_ += counted;
    }
    size_t budget_;
    size_t held_ = 0;
    std::map<std::pair<int, int>, Set> sets_;  // by (light index, cluster)
};

}  // namespace ss
