// How one light sample's shadow edges reach the receiver plane: potential silhouette edges of
// closed meshes (front/back facing change, open edges too), or every front-facing triangle of
// other meshes, projected as directed edges with the shadow on the right.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <vector>

#include "core/scene.h"
#include "methods/sweep/receiver.h"
#include "planar/snap.h"
#include "sampling/light_samples.h"

namespace ss {

struct ProjectionStats {
    size_t silhouetteEdges = 0;     // from closed meshes
    size_t fallbackTriangles = 0;   // front faces projected whole (open, inconsistent, clipped)
    // Occluders projected for this shadow, and those whose projections an earlier shadow of the
    // same light, plane and samples had made (SweepProjectionCache).
    int meshesProjected = 0, meshesReused = 0;
};

// Occluders: the meshes other than the receiver that shadow light `lightIndex` (Scene::castsFor).
std::vector<int> sweepOccluders(const Scene& scene, int lightIndex, const ReceiverPlane& plane);

// Whether a mesh can use silhouette edges (closed, consistently oriented, manifold).
bool usesSilhouettes(const Mesh& mesh);

// Whether the sample casts onto the plane: a positional sample above it, a sun shining on it.
bool castsOntoPlane(const ReceiverPlane& plane, const LightSample& sample);

// Appends one mesh's shadow edges for a sample that casts onto the plane, in grid coordinates.
void projectMeshSample(const Mesh& mesh, const ReceiverPlane& plane, const planar::Snap& snap,
                       const LightSample& sample, std::vector<planar::DirectedEdge>* out, ProjectionStats* stats);

// Appends the sample's shadow edges (every occluder's, in order) in grid coordinates. A sample not above the plane casts
// nothing (returns false): it is below the receiver's horizon and counts in neither irradiance.
bool projectSample(const Scene& scene, const std::vector<int>& occluders, const ReceiverPlane& plane,
                   const planar::Snap& snap, const LightSample& sample,
                   std::vector<planar::DirectedEdge>* out, ProjectionStats* stats);

}  // namespace ss
