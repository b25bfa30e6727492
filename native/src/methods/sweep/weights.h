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

// Reweights `mesh` (from fillShadow over these samples' outlines, in the same order): each
// triangle's shadowing samples S are found at its centroid (strictly inside one trapezoid, so on
// no outline); at each corner v, with W_S(v) and W(v) the weights of S and of all samples there,
// steps fill: I = W_S / W (the weighted Monte Carlo estimate);
// smooth fill: I = I_equal * (W_S / W) / (c / n), the equal-weight ramp scaled by the region's
//   weighted-to-equal ratio (1 in the umbra, where S holds every sample).
// Corners are unshared afterwards (each triangle gets its own three vertices).
void weighShadowMesh(planar::ShadowMesh& mesh, std::span<const std::vector<planar::DirectedEdge>> outlines,
                     std::span<const LightSample> samples, const Light& light, const ReceiverPlane& plane,
                     const planar::Snap& snap, planar::FillMode fill);

}  // namespace ss
