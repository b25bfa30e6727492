// Which points a light reaches at all (E_L > 0 in DESIGN.md): the `mask` every method agrees on.
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_COMMON_VISIBILITY_CONTRACT_GLSL
#define SS_COMMON_VISIBILITY_CONTRACT_GLSL
#include "common/light.glsl"

// P: world point, N: its unit geometric normal (facing the camera). True when some part of the
// light both emits towards P and lies above P's horizon. Mirrors ss::lightReaches()
// (pipeline/visibility_contract.h); keep the two identical.
bool lightReaches(vec3 P, vec3 N) {
    if (uLight.type == LIGHT_SUN) {
        // Some of the sun's disk is above the horizon when the angle between N and the
        // direction to the sun is below 90 degrees plus the sun's angular radius.
        return dot(N, -uLight.direction) > -uLight.sinHalfSun;
    }
    vec3 toLight = uLight.position - P;
    if (uLight.type <= LIGHT_RECTANGLE) {
        // One-sided emitter: P must be strictly in front of the light's plane.
        if (dot(-toLight, uLight.direction) <= 0.0) return false;
        // Highest point of the light above P's tangent plane: centre plus the support of the
        // shape (ellipse: Euclidean norm of the axis projections, rectangle: sum of absolutes).
        float nx = dot(N, uLight.halfAxisX);
        float ny = dot(N, uLight.halfAxisY);
        bool round = uLight.type == LIGHT_DISK || uLight.type == LIGHT_ELLIPSE;
        float reach = round ? sqrt(nx * nx + ny * ny) : abs(nx) + abs(ny);
        return dot(N, toLight) + reach > 0.0;
    }
    float d = length(toLight);
    if (uLight.type == LIGHT_SPOT && dot(-toLight, uLight.direction) < uLight.cosHalfSpot * d)
        return false;
    return dot(N, toLight) + uLight.radius > 0.0;
}

#endif
