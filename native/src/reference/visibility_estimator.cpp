// How the weighted visible share of a light is summed at one surface point.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/visibility_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace ss {

float shadowRayOffset(const SurfaceHit& hit, float sceneExtent) {
    // The traversal's error grows with the coordinates near the point, not with the farthest
    // vertex: one stray vertex at 1e6 must not lift every shadow ray off its surface by a metre.
    const glm::vec3 a = glm::abs(hit.point);
    const float local = std::min(sceneExtent, std::max({a.x, a.y, a.z, 1.0f}));
    return 4.0f * glm::dot(glm::abs(hit.normal), hit.pointError) + 1e-6f * local;
}

namespace {

// The shadow ray from `origin` (the hit pushed off its surface) towards sample `s`: false when
// the sample is below the horizon, sends nothing or coincides with the origin.
bool shadowRay(const SurfaceHit& hit, const glm::vec3& origin, const ShadowRay& s, glm::vec3* dir, float* tFar,
               double* weight) {
    const float cosSurface = glm::dot(hit.normal, s.toLight);
    if (!(cosSurface > 0.0f) || !(s.weight > 0.0f)) return false;  // below the horizon / dark
    *dir = s.toLight;
    *tFar = s.distance;
    if (std::isfinite(s.distance)) {
        // Aim from the offset origin at the very sample point; stop just short of it so a
        // mesh the light lies on does not shadow it.
        const glm::vec3 v = hit.point + s.distance * s.toLight - origin;
        const float len = glm::length(v);
        if (!(len > 0.0f)) return false;
        *dir = v / len;
        *tFar = len * (1.0f - 1e-5f);
    }
    *weight = double(s.weight) * double(cosSurface);
    return true;
}

}  // namespace

bool lightCentreVisible(const TraceScene& scene, const LightSampler& light, const SurfaceHit& hit,
                        bool castShadows) {
    const glm::vec3 origin = hit.point + shadowRayOffset(hit, scene.extent()) * hit.normal;
    glm::vec3 dir;
    float tFar;
    double weight;
    if (!castShadows || !shadowRay(hit, origin, light.sample(hit.point, glm::vec2(0.5f)), &dir, &tFar, &weight))
        return true;
    return scene.transmission(origin, dir, tFar, hit.mesh, hit.triangle) > 0.5f;
}

void addSamples(const TraceScene& scene, const LightSampler& light, const SurfaceHit& hit,
                const SampleSequence& sequence, uint32_t begin, uint32_t end, bool castShadows,
                SampleSums* sums) {
    const glm::vec3 origin = hit.point + shadowRayOffset(hit, scene.extent()) * hit.normal;
    // Per-thread scratch: one pixel's rays are gathered first and traced as packets.
    thread_local std::vector<glm::vec3> dirs;
    thread_local std::vector<float> tFars;
    thread_local std::vector<double> weights;
    thread_local std::vector<float> through;
    dirs.clear(), tFars.clear(), weights.clear();
    for (uint32_t i = begin; i < end; ++i) {
        glm::vec3 dir;
        float tFar;
        double weight;
        if (!shadowRay(hit, origin, light.sample(hit.point, sequence.point(i)), &dir, &tFar, &weight)) continue;
        dirs.push_back(dir);
        tFars.push_back(tFar);
        weights.push_back(weight);
    }
    through.assign(weights.size(), 1.0f);
    if (castShadows && !weights.empty()) {
        scene.transmissionMany(origin, dirs.data(), tFars.data(), dirs.size(), hit.mesh, hit.triangle,
                               through.data());
        sums->rays += int(weights.size());
        for (float t : through) {
            sums->leastThrough = std::min(sums->leastThrough, t);
            sums->mostThrough = std::max(sums->mostThrough, t);
        }
    }
    // Double sums in sample order: 4096 samples of widely varying weight must not lose the
    // small ones, and with nothing hidden the two sums are bit-identical (V == 1 exactly).
    for (size_t i = 0; i < weights.size(); ++i) {
        sums->weight += weights[i];
        if (through[i] == 1.0f) sums->visible += weights[i];
        else if (through[i] > 0.0f) sums->visible += weights[i] * double(through[i]);
    }
}

PointVisibility estimateVisibility(const TraceScene& scene, const LightSampler& light,
                                   const SurfaceHit& hit, const SampleSequence& sequence,
                                   int samples, bool castShadows) {
    SampleSums sums;
    addSamples(scene, light, hit, sequence, 0, uint32_t(samples), castShadows, &sums);
    PointVisibility out;
    if (sums.weight > 0.0) {
        out.reached = true;
        out.visibility = float(sums.visible / sums.weight);
    }
    return out;
}

}  // namespace ss
