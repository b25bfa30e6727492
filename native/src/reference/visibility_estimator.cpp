// How the weighted visible share of a light is summed at one surface point.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/visibility_estimator.h"

#include <cmath>

namespace ss {

float shadowRayOffset(const SurfaceHit& hit, float sceneExtent) {
    return 4.0f * glm::dot(glm::abs(hit.normal), hit.pointError) + 1e-6f * sceneExtent;
}

PointVisibility estimateVisibility(const TraceScene& scene, const LightSampler& light,
                                   const SurfaceHit& hit, const SampleSequence& sequence,
                                   int samples, bool castShadows) {
    const glm::vec3 origin = hit.point + shadowRayOffset(hit, scene.extent()) * hit.normal;
    // Double sums: 4096 samples of widely varying weight must not lose the small ones.
    double sumWeight = 0.0, sumVisible = 0.0;
    for (int i = 0; i < samples; ++i) {
        LightSample s = light.sample(hit.point, sequence.point(uint32_t(i)));
        float cosSurface = glm::dot(hit.normal, s.toLight);
        if (!(cosSurface > 0.0f) || !(s.weight > 0.0f)) continue;
        double w = double(s.weight) * double(cosSurface);
        glm::vec3 dir = s.toLight;
        float tFar = s.distance;
        if (std::isfinite(s.distance)) {
            // Aim from the offset origin at the very sample point; stop just short of it so a
            // mesh the light lies on does not shadow it.
            glm::vec3 v = hit.point + s.distance * s.toLight - origin;
            float len = glm::length(v);
            if (!(len > 0.0f)) continue;
            dir = v / len;
            tFar = len * (1.0f - 1e-5f);
        }
        sumWeight += w;
        if (!castShadows || !scene.occluded(origin, dir, tFar, hit.mesh, hit.triangle)) sumVisible += w;
    }
    PointVisibility out;
    if (sumWeight > 0.0) {
        out.reached = true;
        out.visibility = float(sumVisible / sumWeight);
    }
    return out;
}

}  // namespace ss
