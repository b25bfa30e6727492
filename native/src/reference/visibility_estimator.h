// How V at one surface point is estimated from light samples (the visibility contract).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "reference/light_sampler.h"
#include "reference/sample_sequence.h"
#include "reference/trace_scene.h"

namespace ss {

struct PointVisibility {
    float visibility = 1.0f;  // V in [0, 1]; 1 when the light does not reach the point
    bool reached = false;     // E_L > 0: some sample above the horizon carries weight
};

// The running sums of a point's light samples, in sample order (V = visible / weight).
struct SampleSums {
    double weight = 0.0, visible = 0.0;
    int rays = 0;          // shadow rays traced (samples above the horizon with weight > 0)
    // The least and the most transmission of those rays (1 and 0 before the first).
    float leastThrough = 1.0f, mostThrough = 0.0f;
    double visibility() const { return weight > 0.0 ? visible / weight : 1.0; }
    // Every traced sample agrees: all let through the same share (all blocked, all visible, or
    // all behind the same see-through surface).
    bool agree() const { return rays == 0 || leastThrough == mostThrough; }
};

// Adds samples [begin, end) of `sequence` to *sums (the estimator below, in pieces: rounds of
// the adaptive sampling continue where the previous round stopped, with the same sums).
void addSamples(const TraceScene& scene, const LightSampler& light, const SurfaceHit& hit,
                const SampleSequence& sequence, uint32_t begin, uint32_t end, bool castShadows,
                SampleSums* sums);

// V = sum_s w_s T_s / sum_s w_s (T_s the shadow ray's transmission, TraceScene::transmission) over `samples` points of `sequence`, w_s = the sample's
// weight times the cosine at the surface; samples at or below the horizon of `hit.normal`
// count in neither sum. Shadow rays start at the point pushed off the surface by its error
// bound (plus a sliver of the scene's extent) and ignore the triangle they start on. Without
// castShadows no ray is traced (V = 1 wherever E_L > 0).
PointVisibility estimateVisibility(const TraceScene& scene, const LightSampler& light,
                                   const SurfaceHit& hit, const SampleSequence& sequence,
                                   int samples, bool castShadows = true);

// Whether the light's centre (the sample at u = (0.5, 0.5): the middle of an area light or of a
// sphere light's disk, a sun's central direction) is unblocked from `hit` (more than half of it
// let through), with the same ray
// set-up as the samples: the hard shadow a light-centre shadow map approximates. True where the
// centre is below the horizon or sends nothing (no shadow to speak of there).
bool lightCentreVisible(const TraceScene& scene, const LightSampler& light, const SurfaceHit& hit,
                        bool castShadows);

// The distance a shadow ray's origin is moved along the normal: the projected rounding error
// of the point, 4x for safety, plus 1e-6 of the point's largest coordinate (at least 1, at most
// the scene extent) for the traversal's own error.
float shadowRayOffset(const SurfaceHit& hit, float sceneExtent);

}  // namespace ss
