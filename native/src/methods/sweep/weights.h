// How the sweep's shadow mesh weighs each light sample by the irradiance it sends to a receiver
// point (cosines at both ends, inverse square distance), as the visibility contract does.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <span>
#include <vector>

#include "core/light.h"
#include "methods/sweep/receiver.h"
#include "planar/penumbra_fill.h"
#include "planar/snap.h"
#include "sampling/light_samples.h"

namespace ss {

// The irradiance one sample of `light` sends to point p of a surface with unit normal n, up to
// a constant common to all samples: cos_light * cos_receiver / d^2 (area lights), cos_receiver
// / d^2 (a sphere's disk facing the occluders), cos_receiver (sun). 0 below p's horizon.
double sampleIrradianceWeight(const Light& light, const LightSample& s, const glm::dvec3& p, const glm::dvec3& n);

// What one weighting of a light's shadow leaves for the next (SweepProjectionCache keeps it per
// light and cluster): each sample's outline and each weighted triangle, looked up by its corners.
// A triangle is weighed again unless the same triangle was weighed last time and its centroid
// lies outside, for every sample, the bounding box of the outline edges that changed since: the
// edges that differ form closed cycles, which wind zero times around any point outside their
// box, so the samples shadowing the centroid, and with them the triangle's weights, are the same.
struct WeightedTriangles {
    planar::FillMode fill = planar::FillMode::Smooth;
    glm::dvec3 emits{0.0};  // the emitter's direction (0 for no cosine there)
    std::vector<std::vector<planar::DirectedEdge>> outlines;
    struct Triangle {
        double x[3], y[3];
        float in[3], out[3];  // corner intensities before and after weighing
    };
    std::vector<Triangle> triangles;
    std::vector<uint32_t> slots;  // open addressing by corners: triangle index + 1, 0 = empty
    size_t bytes() const;
    void clear();
};

// Triangles weighed by one call, and those taken from WeightedTriangles instead.
struct WeightStats {
    size_t trianglesWeighed = 0, trianglesReused = 0;
};

// Reweights `mesh` (from fillShadow over these samples' outlines, in the same order): each
// triangle's shadowing samples S are found at its centroid (strictly inside one trapezoid, so on
// no outline); at each corner v, with W_S(v) and W(v) the weights of S and of all samples there,
// steps fill: I = W_S / W (the weighted Monte Carlo estimate);
// smooth fill: I = I_equal * (W_S / W) / (c / n), the equal-weight ramp scaled by the region's
//   weighted-to-equal ratio (1 in the umbra, where S holds every sample).
// Corners are unshared afterwards (each triangle gets its own three vertices).
void weighShadowMesh(planar::ShadowMesh& mesh, std::span<const std::vector<planar::DirectedEdge>> outlines,
                     std::span<const LightSample> samples, const Light& light, const ReceiverPlane& plane,
                     const planar::Snap& snap, planar::FillMode fill, WeightStats* stats = nullptr);
// The same, reusing what `kept` holds from an earlier call with these samples, light, plane and
// snap (the result is the same bit for bit), and leaving this call's triangles in it.
void weighShadowMesh(planar::ShadowMesh& mesh, std::span<const std::vector<planar::DirectedEdge>> outlines,
                     std::span<const LightSample> samples, const Light& light, const ReceiverPlane& plane,
                     const planar::Snap& snap, planar::FillMode fill, WeightedTriangles& kept, WeightStats* stats);

}  // namespace ss
