// How E_L > 0 is tested on the CPU: a line-for-line copy of shaders/common/visibility_contract.glsl.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/visibility_contract.h"

#include <algorithm>
#include <cmath>

namespace ss {

namespace {

// Directions w seen from P: is there one with w.u >= cosA (on the disk facing P), w.s >= cosH
// (inside the spot's cone) and w.N > 0 (above P's horizon)? The caller has already found both
// caps to overlap; the highest point (largest w.N) of their lens is N itself, the highest point
// of one rim lying inside the other cap, or a corner where the rims cross.
bool lensAboveHorizon(glm::vec3 u, float cosA, float sinA, glm::vec3 s, float cosH, float sinH,
                      glm::vec3 N) {
    if (glm::dot(N, u) >= cosA && glm::dot(N, s) >= cosH) return true;
    glm::vec3 tD = N - glm::dot(N, u) * u;
    float lenD = glm::length(tD);
    if (lenD > 1e-7f) {
        glm::vec3 w = cosA * u + sinA * (tD / lenD);
        if (glm::dot(w, s) >= cosH && glm::dot(N, w) > 0.0f) return true;
    }
    glm::vec3 tS = N - glm::dot(N, s) * s;
    float lenS = glm::length(tS);
    if (lenS > 1e-7f) {
        glm::vec3 w = cosH * s + sinH * (tS / lenS);
        if (glm::dot(w, u) >= cosA && glm::dot(N, w) > 0.0f) return true;
    }
    // Corners w = x u + y s + z m / |m|, m = u x s, on both rims: w.u = cosA, w.s = cosH.
    glm::vec3 m = glm::cross(u, s);
    float mm = glm::dot(m, m);
    if (mm > 1e-12f) {
        float g = glm::dot(u, s);
        float x = (cosA - cosH * g) / mm, y = (cosH - cosA * g) / mm;
        float z2 = (mm - cosA * cosA - cosH * cosH + 2.0f * cosA * cosH * g) / mm;
        if (z2 >= 0.0f && x * glm::dot(N, u) + y * glm::dot(N, s) +
                                  std::sqrt(z2) * std::abs(glm::dot(N, m)) / std::sqrt(mm) >
                              0.0f)
            return true;
    }
    return false;
}

}  // namespace

bool lightReaches(const Light& light, const glm::vec3& P, const glm::vec3& N) {
    // The uniforms the GLSL twin reads (SceneCache::setLightUniforms), derived the same way.
    const glm::vec3 position = light.position(), direction = light.direction();
    const float radius = light.radius;
    const float cosHalfSpot = std::cos(0.5f * light.spotSize);
    const float sinHalfSun = std::sin(light.sunHalfAngle());

    if (light.type == LightType::Sun) {
        // Some of the sun's cone is above the horizon when the angle between N and the
        // direction to the sun is below 90 degrees plus the sun's angular radius.
        return glm::dot(N, -direction) > -sinHalfSun;
    }
    glm::vec3 toLight = position - P;
    if (light.isArea()) {
        // One-sided emitter: P must be strictly in front of the light's plane (then every point
        // of the light emits towards P, so this and the horizon test are independent).
        if (glm::dot(-toLight, direction) <= 0.0f) return false;
        // Highest point of the light above P's tangent plane: centre plus the support of the
        // shape (ellipse: Euclidean norm of the axis projections, rectangle: sum of absolutes).
        float nx = glm::dot(N, light.halfAxisX());
        float ny = glm::dot(N, light.halfAxisY());
        bool round = light.type == LightType::Disk || light.type == LightType::Ellipse;
        float reach = round ? std::sqrt(nx * nx + ny * ny) : std::abs(nx) + std::abs(ny);
        return glm::dot(N, toLight) + reach > 0.0f;
    }
    // Point/spot: a disk of the light's radius centred on it and facing P (its normal is
    // toLight / d). Inside the sphere the reference gives every sample weight 0.
    float d = glm::length(toLight);
    if (!(d > radius)) return false;
    // Horizon: the disk's highest point above P's tangent plane is the centre's height plus
    // radius times the sine of the angle between N and the disk's normal.
    float up = glm::dot(N, toLight);
    float cosN = up / d;
    if (!(up + radius * std::sqrt(std::max(0.0f, 1.0f - cosN * cosN)) > 0.0f)) return false;
    if (light.type == LightType::Spot) {
        // Seen from P the facing disk is a circular cone of half-angle alpha = atan(r / d)
        // around -toLight (directions from the disk to P), so some point of the disk sends
        // light to P inside the spot's cone (half-angle h) iff the angle theta between the axis
        // and -toLight is below h + alpha. h <= 90 deg and alpha < 45 deg, so h + alpha < 180 deg
        // and the test is cos(theta) > cos(h + alpha) = cos h cos alpha - sin h sin alpha.
        float hyp = std::sqrt(d * d + radius * radius);
        float cosTheta = glm::dot(-toLight, direction) / d;
        float sinHalfSpot = std::sqrt(std::max(0.0f, 1.0f - cosHalfSpot * cosHalfSpot));
        if (!(cosTheta > (cosHalfSpot * d - sinHalfSpot * radius) / hyp)) return false;
        // Both hold, but one sample must satisfy both: the disk's part inside the cone must
        // rise above the horizon (matters where the cone's rim and the horizon cut the disk).
        return lensAboveHorizon(toLight / d, d / hyp, radius / hyp, -direction, cosHalfSpot,
                                sinHalfSpot, N);
    }
    return true;
}

}  // namespace ss
