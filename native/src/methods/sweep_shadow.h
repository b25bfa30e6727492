// What the sweep method computes on the CPU for one light: the light samples, each sample's
// hard outline, the merged rings and the shadow mesh on the receiver plane, with stage timings.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <vector>

#include "core/scene.h"
#include "methods/method.h"
#include "methods/sweep_projection.h"
#include "methods/sweep_receiver.h"
#include "planar/penumbra_fill.h"

namespace ss {

constexpr int kSweepDefaultSamples = 16;

struct SweepOptions {
    int samples = kSweepDefaultSamples;
    uint32_t seed = 1;
    double borderShare = 0.25;
    planar::FillMode fill = planar::FillMode::Smooth;
    std::string receiver;  // mesh name; empty = the largest planar receiver
};

// Reads RenderSettings: samples (0 = 16), seed, options "receiver", "fill" (smooth|steps),
// "border" (share of samples on the light's border, 0..1). Throws ss::Error on bad values.
SweepOptions sweepOptions(const RenderSettings& settings);

struct SweepTimings {
    double silhouettesMs = 0, sweepMs = 0, mergeMs = 0, fillMs = 0;
};

struct SweepShadow {
    ReceiverPlane plane;
    planar::Snap snap{0, 0, 1};
    planar::ShadowMesh mesh;        // grid coordinates
    int samplesUsed = 0;            // samples above the receiver plane
    ProjectionStats projection;
    SweepTimings timings;
    // World position of a shadow-mesh vertex.
    glm::dvec3 worldVertex(size_t i) const {
        return plane.toWorld(snap.toU(mesh.vertices[i].x), snap.toV(mesh.vertices[i].y));
    }
};

SweepShadow computeSweepShadow(const Scene& scene, int lightIndex, const SweepOptions& options);

}  // namespace ss
