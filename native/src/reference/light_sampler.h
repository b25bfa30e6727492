// Where a light sends irradiance from: one point (or sun direction) per 2D sample, and its weight.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <glm/glm.hpp>

#include "core/light.h"

namespace ss {

// One shadow ray: a sample of a light as seen from a shading point (sampling/light_samples.h's
// LightSample is a point on the light, for the sweep). The weight is the irradiance the sample
// sends up to the cosine at the receiver (which the caller applies, because only it knows the
// surface normal) and up to a constant per light, so sums of weights are proportional to E_L.
struct ShadowRay {
    glm::vec3 toLight{0.0f};  // unit, from the shading point towards the sample
    float distance = 0.0f;    // to the sample point; +infinity for a sun
    float weight = 0.0f;      // >= 0; 0 when this part of the light sends nothing to the point
};

// Samples every Light shape uniformly in the measure its radiance is constant in, so one weight
// formula per shape is exact:
// - area (disk/ellipse: concentric map; square/rectangle: the parallelogram of the half axes):
//   uniform in area, weight = max(0, cos at the light) / d^2 (one-sided, emits along -Z);
// - point/spot with radius r: as Cycles 3.0-3.4 (Blender 3.4 is the target), a disk of radius r
//   centred on the light and facing the shading point, uniform in area, weight = 1 / d^2 (Cycles
//   3.5+ adds the disk's cosine; at r << d the two agree); r = 0 is the point itself; a
//   shading point inside the sphere gets weight 0. Spots multiply by Cycles 3.x's
//   spot_attenuation (cos to the axis, smoothstep over the blend, 0 outside the cone), evaluated
//   along the direction from the sample to the shading point;
// - sun: directions uniform in solid angle inside the cone of half-angle angle/2, weight 1.
class LightSampler {
public:
    explicit LightSampler(const Light& light);
    // u in [0,1)^2; the mapping is continuous and measure-preserving so stratification survives.
    ShadowRay sample(const glm::vec3& point, glm::vec2 u) const;

private:
    ShadowRay sampleArea(const glm::vec3& point, glm::vec2 u) const;
    ShadowRay sampleSphere(const glm::vec3& point, glm::vec2 u) const;
    ShadowRay sampleSun(glm::vec2 u) const;
    float spotFactor(const glm::vec3& fromLight) const;

    LightType type_;
    glm::vec3 centre_, emit_, halfX_, halfY_;
    float radius_ = 0.0f;
    float cosHalfSpot_ = -1.0f, spotSmooth_ = 0.0f;
    glm::vec3 toSun_, sunT_, sunB_;
    float sunOneMinusCos_ = 0.0f;
};

// Shirley-Chiu concentric map of the unit square onto the unit disk (area-preserving).
glm::vec2 concentricDisk(glm::vec2 u);
// Two unit vectors completing n (unit) to a right-handed orthonormal basis.
void orthonormalBasis(const glm::vec3& n, glm::vec3* t, glm::vec3* b);

}  // namespace ss
