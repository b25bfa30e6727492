// Which points a light reaches (E_L > 0): the mask every method uses; ss::lightReaches() is a copy.
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_COMMON_VISIBILITY_CONTRACT_GLSL
#define SS_COMMON_VISIBILITY_CONTRACT_GLSL
#include "common/light.glsl"

// Directions w seen from P: is there one with w.u >= cosA (on the disk facing P), w.s >= cosH
// (inside the spot's cone) and w.N > 0 (above P's horizon)? The caller has already found both
// caps to overlap; the highest point (largest w.N) of their lens is N itself, the highest point
// of one rim lying inside the other cap, or a corner where the rims cross.
bool lensAboveHorizon(vec3 u, float cosA, float sinA, vec3 s, float cosH, float sinH, vec3 N) {
    if (dot(N, u) >= cosA && dot(N, s) >= cosH) return true;
    vec3 tD = N - dot(N, u) * u;
    float lenD = length(tD);
    if (lenD > 1e-7) {
        vec3 w = cosA * u + sinA * (tD / lenD);
        if (dot(w, s) >= cosH && dot(N, w) > 0.0) return true;
    }
    vec3 tS = N - dot(N, s) * s;
    float lenS = length(tS);
    if (lenS > 1e-7) {
        vec3 w = cosH * s + sinH * (tS / lenS);
        if (dot(w, u) >= cosA && dot(N, w) > 0.0) return true;
    }
    // Corners w = x u + y s + z m / |m|, m = u x s, on both rims: w.u = cosA, w.s = cosH.
    vec3 m = cross(u, s);
    float mm = dot(m, m);
    if (mm > 1e-12) {
        float g = dot(u, s);
        float x = (cosA - cosH * g) / mm, y = (cosH - cosA * g) / mm;
        float z2 = (mm - cosA * cosA - cosH * cosH + 2.0 * cosA * cosH * g) / mm;
        if (z2 >= 0.0 && x * dot(N, u) + y * dot(N, s) + sqrt(z2) * abs(dot(N, m)) / sqrt(mm) > 0.0)
            return true;
    }
    return false;
}

// P: world point, N: its unit geometric normal (facing the camera). True exactly when the
// `reference` method's light samples can carry weight to P above its horizon; the rule per light
// shape is written out at ss::lightReaches() (pipeline/visibility_contract.h), whose code is a
// line-for-line copy of these two functions: keep them identical.
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
        // Both hold, but one sample must satisfy both: the disk's part inside the cone must
        // rise above the horizon (matters where the cone's rim and the horizon cut the disk).
        return lensAboveHorizon(toLight / d, d / hyp, radius / hyp, -uLight.direction, cosHalfSpot,
                                sinHalfSpot, N);
    }
    return true;
}

#endif
