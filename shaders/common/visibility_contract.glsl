// Which points a light reaches (E_L > 0): the mask every method uses; ss::lightReaches() is a copy.
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_COMMON_VISIBILITY_CONTRACT_GLSL
#define SS_COMMON_VISIBILITY_CONTRACT_GLSL
#include "common/light.glsl"

// P: world point, N: its unit geometric normal (facing the camera). True exactly when the
// `reference` method's light samples can carry weight to P above its horizon; the rule per light
// shape is written out at ss::lightReaches() (pipeline/visibility_contract.h), whose code is a
// line-for-line copy of this function: keep the two identical.
bool lightReaches(vec3 P, vec3 N) {
    if (uLight.type == LIGHT_SUN) {
        // Some of the sun's cone is above the horizon when the angle between N and the
        // direction to the sun is below 90 degrees plus the sun's angular radius.
        return dot(N, -uLight.direction) > -uLight.sinHalfSun;
    }
    vec3 toLight = uLight.position - P;
    if (uLight.type <= LIGHT_RECTANGLE) {
        // One-sided emitter: P must be strictly in front of the light's plane (then every point
        // of the light emits towards P, so this and the horizon test are independent).
        if (dot(-toLight, uLight.direction) <= 0.0) return false;
        // Highest point of the light above P's tangent plane: centre plus the support of the
        // shape (ellipse: Euclidean norm of the axis projections, rectangle: sum of absolutes).
        float nx = dot(N, uLight.halfAxisX);
        float ny = dot(N, uLight.halfAxisY);
        bool round = uLight.type == LIGHT_DISK || uLight.type == LIGHT_ELLIPSE;
        float reach = round ? sqrt(nx * nx + ny * ny) : abs(nx) + abs(ny);
        return dot(N, toLight) + reach > 0.0;
    }
    // Point/spot: a disk of the light's radius centred on it and facing P (its normal is
    // toLight / d). Inside the sphere the reference gives every sample weight 0.
    float radius = uLight.radius;
    float d = length(toLight);
    if (!(d > radius)) return false;
    // Horizon: the disk's highest point above P's tangent plane is the centre's height plus
    // radius times the sine of the angle between N and the disk's normal.
    float up = dot(N, toLight);
    float cosN = up / d;
    if (!(up + radius * sqrt(max(0.0, 1.0 - cosN * cosN)) > 0.0)) return false;
    if (uLight.type == LIGHT_SPOT) {
        // Seen from P the facing disk is a circular cone of half-angle alpha = atan(r / d)
        // around -toLight (directions from the disk to P), so some point of the disk sends
        // light to P inside the spot's cone (half-angle h) iff the angle theta between the axis
        // and -toLight is below h + alpha. h <= 90 deg and alpha < 45 deg, so h + alpha < 180 deg
        // and the test is cos(theta) > cos(h + alpha) = cos h cos alpha - sin h sin alpha.
        float hyp = sqrt(d * d + radius * radius);
        float cosTheta = dot(-toLight, uLight.direction) / d;
        float cosHalfSpot = uLight.cosHalfSpot;
        float sinHalfSpot = sqrt(max(0.0, 1.0 - cosHalfSpot * cosHalfSpot));
        if (!(cosTheta > (cosHalfSpot * d - sinHalfSpot * radius) / hyp)) return false;
    }
    return true;
}

#endif
