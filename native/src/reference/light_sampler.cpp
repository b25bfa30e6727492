// How each light shape is sampled and what irradiance weight each sample carries.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/light_sampler.h"

#include <cmath>
#include <limits>

namespace ss {

glm::vec2 concentricDisk(glm::vec2 u) {
    glm::vec2 o = 2.0f * u - 1.0f;
    if (o.x == 0.0f && o.y == 0.0f) return {0.0f, 0.0f};
    float r, theta;
    constexpr float kQuarterPi = float(M_PI) / 4.0f;
    if (std::abs(o.x) > std::abs(o.y)) {
        r = o.x;
        theta = kQuarterPi * (o.y / o.x);
    } else {
        r = o.y;
        theta = 2.0f * kQuarterPi - kQuarterPi * (o.x / o.y);
    }
    return r * glm::vec2(std::cos(theta), std::sin(theta));
}

void orthonormalBasis(const glm::vec3& n, glm::vec3* t, glm::vec3* b) {
    // Duff et al. 2017: branchless and stable for every unit n.
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    *t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

LightSampler::LightSampler(const Light& light)
    : type_(light.type),
      centre_(light.position()),
      emit_(light.direction()),
      halfX_(light.isArea() ? light.halfAxisX() : glm::vec3(0.0f)),
      halfY_(light.isArea() ? light.halfAxisY() : glm::vec3(0.0f)),
      radius_(light.radius) {
    if (type_ == LightType::Spot) {
        // Cycles 3.x: spot_angle = cos(size / 2), spot_smooth = (1 - spot_angle) * blend.
        cosHalfSpot_ = std::cos(0.5f * light.spotSize);
        spotSmooth_ = (1.0f - cosHalfSpot_) * light.spotBlend;
    }
    toSun_ = -emit_;
    orthonormalBasis(toSun_, &sunT_, &sunB_);
    // 1 - cos(a) written as 2 sin^2(a/2): no cancellation for the tiny angles suns use.
    float s = std::sin(0.25f * light.angle);
    sunOneMinusCos_ = 2.0f * s * s;
}

ShadowRay LightSampler::sample(const glm::vec3& point, glm::vec2 u) const {
    switch (type_) {
        case LightType::Disk:
        case LightType::Ellipse:
        case LightType::Square:
        case LightType::Rectangle: return sampleArea(point, u);
        case LightType::Point:
        case LightType::Spot: return sampleSphere(point, u);
        case LightType::Sun: return sampleSun(u);
    }
    return {};
}

ShadowRay LightSampler::sampleArea(const glm::vec3& point, glm::vec2 u) const {
    glm::vec2 local = (type_ == LightType::Disk || type_ == LightType::Ellipse)
                          ? concentricDisk(u)
                          : 2.0f * u - 1.0f;
    glm::vec3 onLight = centre_ + local.x * halfX_ + local.y * halfY_;
    glm::vec3 v = onLight - point;
    float d = glm::length(v);
    ShadowRay s;
    if (!(d > 0.0f)) return s;
    s.toLight = v / d;
    s.distance = d;
    float cosLight = -glm::dot(emit_, s.toLight);
    s.weight = cosLight > 0.0f ? cosLight / (d * d) : 0.0f;
    return s;
}

ShadowRay LightSampler::sampleSphere(const glm::vec3& point, glm::vec2 u) const {
    glm::vec3 fromCentre = point - centre_;
    float dc = glm::length(fromCentre);
    ShadowRay s;
    if (!(dc > radius_)) return s;  // inside the sphere (or on the point light itself)
    glm::vec3 onLight = centre_;
    glm::vec3 diskNormal = fromCentre / dc;
    if (radius_ > 0.0f) {
        glm::vec3 t, b;
        orthonormalBasis(diskNormal, &t, &b);
        glm::vec2 q = radius_ * concentricDisk(u);
        onLight += q.x * t + q.y * b;
    }
    glm::vec3 v = onLight - point;
    float d = glm::length(v);
    s.toLight = v / d;
    s.distance = d;
    // Cycles 3.0-3.4 evaluates the sample with its light normal set to -D, so the disk's own
    // cosine is 1 in lamp_light_pdf: the weight is the inverse square alone.
    float w = 1.0f / (d * d);
    if (type_ == LightType::Spot) w *= spotFactor(-s.toLight);
    s.weight = w;
    return s;
}

float LightSampler::spotFactor(const glm::vec3& fromLight) const {
    float att = glm::dot(emit_, fromLight);
    if (att <= cosHalfSpot_) return 0.0f;
    float t = att - cosHalfSpot_;
    if (spotSmooth_ != 0.0f && t < spotSmooth_) {
        float x = t / spotSmooth_;
        att *= x * x * (3.0f - 2.0f * x);
    }
    return att;
}

ShadowRay LightSampler::sampleSun(glm::vec2 u) const {
    // The concentric disk point has r^2 uniform; cos(theta) = 1 - r^2 (1 - cos a) maps it onto
    // the spherical cap with equal solid angle per area (Archimedes).
    glm::vec2 q = concentricDisk(u);
    float r2 = glm::dot(q, q);
    float oneMinusCos = r2 * sunOneMinusCos_;
    float cosTheta = 1.0f - oneMinusCos;
    float sinTheta = std::sqrt(std::max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
    glm::vec3 dir = cosTheta * toSun_;
    if (r2 > 0.0f) {
        float scale = sinTheta / std::sqrt(r2);
        dir += scale * (q.x * sunT_ + q.y * sunB_);
    }
    ShadowRay s;
    s.toLight = glm::normalize(dir);
    s.distance = std::numeric_limits<float>::infinity();
    s.weight = 1.0f;
    return s;
}

}  // namespace ss
