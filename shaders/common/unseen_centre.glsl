// How the hard-shadow methods test a point whose light centre is below its horizon: a march
// through the light-centre map towards the part of the light the point does see.
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_COMMON_UNSEEN_CENTRE_GLSL
#define SS_COMMON_UNSEEN_CENTRE_GLSL
#include "common/light.glsl"
#include "common/shadow_map.glsl"

// The map's ray from the centre reaches such a point P through P's own unlit side, so the texel
// at P holds no blocker (centreAboveHorizon). Blockers of the light P sees lie in front of P's
// tangent plane, on the way to that part of the light: a concave caster's own brow over its eye,
// which the map shows between the centre and points of the segment from P towards the middle of
// the light's part above P's horizon. The march takes points X on that segment, nearer P first
// (kUnseenCentreSteps, each sqrt(2) times as far as the last), and calls P shadowed when the map's caster
// in front of some X lies in front of P's plane. On a convex caster every caster the map shows in
// front of X lies behind that plane (its own faces) and P stays lit, as the reference has it.
const int kUnseenCentreSteps = 24;

// The middle of the light's part above P's horizon: halfway between the light's point highest
// above P's tangent plane and the point where the line from the centre to it meets that plane.
// false when none of the light is above it, or for a sun (no point of the light in the map).
bool middleOfSeenLight(vec3 P, vec3 N, out vec3 middle) {
    middle = uLight.position;
    if (uLight.type == LIGHT_SUN) return false;
    vec3 toHighest;
    float reach;
    if (lightIsArea()) {
        float nx = dot(N, uLight.halfAxisX), ny = dot(N, uLight.halfAxisY);
        if (uLight.type == LIGHT_DISK || uLight.type == LIGHT_ELLIPSE) {
            reach = sqrt(nx * nx + ny * ny);
            toHighest = nx * uLight.halfAxisX + ny * uLight.halfAxisY;
            toHighest = reach > 0.0 ? toHighest / reach : vec3(0.0);
        } else {
            reach = abs(nx) + abs(ny);
            toHighest = sign(nx) * uLight.halfAxisX + sign(ny) * uLight.halfAxisY;
        }
    } else {
        // Point and spot: the disk of the light's radius facing P.
        vec3 facing = normalize(uLight.position - P);
        vec3 across = N - dot(N, facing) * facing;
        float len = length(across);
        toHighest = len > 0.0 ? uLight.radius * across / len : vec3(0.0);
        reach = uLight.radius * len;
    }
    float height = dot(N, uLight.position - P);  // <= 0 here: the centre is below the horizon
    if (!(reach + height > 0.0)) return false;
    float horizon = -height / reach;  // share of the way to the highest point where it rises above
    middle = uLight.position + 0.5 * (1.0 + horizon) * toHighest;
    return true;
}

// True when the map shows a caster in front of P's tangent plane between the light centre and
// a point of the segment from P to the middle of the light P sees (P: the receiver point, N its
// normal facing the camera). The plane test has a margin of a texel at the caster, the depth
// test one of a texel at X. `needed`: whether P needs the march (its centre below the horizon);
// a loop, not a branch, so that a pixel block where none does pays one pass (docs/gl.md, "What
// costs what on llvmpipe").
bool unseenCentreBlocked(vec3 P, vec3 N, bool needed) {
    vec3 middle;
    bool blocked = false;
    int steps = needed && middleOfSeenLight(P, N, middle) ? kUnseenCentreSteps : 0;
    vec3 toMiddle = middle - P;
    float t = exp2(-0.5 * float(kUnseenCentreSteps));
    for (int i = 0; i < steps && !blocked; ++i) {
        t *= 1.41421356;  // 2^-11.5 ... 1 of the way
        vec3 X = P + t * toMiddle;
        vec2 uv;
        if (!shadowMapUv(X, uv)) continue;
        ivec2 texel = clamp(ivec2(uv * uShadowSize), ivec2(0), ivec2(int(uShadowSize) - 1));
        float z = texelFetch(uShadowDistance, texel, 0).r;
        float dX = shadowDistanceOf(X);
        if (!(z < dX - shadowTexelWorldSize(dX))) continue;
        vec3 S = uShadowOrthographic != 0 ? X - (dX - z) * uShadowAxis
                                          : uShadowOrigin + (X - uShadowOrigin) * (z / dX);
        blocked = dot(N, S - P) > shadowTexelWorldSize(z);
    }
    return blocked;
}

// Whether P's light centre is below its horizon, where the march decides P alone: `visible` is
// then 0 (blocked) or 1. Called by every fragment (the march is a loop, see above).
bool belowHorizonDecides(vec3 P, vec3 N, vec3 toCentre, out float visible) {
    bool seesCentre = centreAboveHorizon(N, toCentre);
    visible = unseenCentreBlocked(P, N, !seesCentre) ? 0.0 : 1.0;
    return !seesCentre;
}

#endif
