// What distance the shadow map would store at a texel if the receiver were the plane (P, N):
// the depth comparison pcss and penumbra_map use instead of a constant bias.
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_PCSS_RECEIVER_PLANE_GLSL
#define SS_PCSS_RECEIVER_PLANE_GLSL
#include "common/shadow_map.glsl"

// Columns: the map's right and up axes scaled by tan(half fov) (perspective) or by the half
// width (orthographic), then its unit view axis. Set by shadowRayBasis() on the C++ side.
uniform mat3 uShadowRayBasis;

// The light ray through map coordinates uv: origin and unit direction.
void shadowRay(vec2 uv, out vec3 origin, out vec3 dir) {
    vec2 ndc = uv * 2.0 - 1.0;
    if (uShadowOrthographic != 0) {
        origin = uShadowOrigin + uShadowRayBasis * vec3(ndc, 0.0);
        dir = uShadowAxis;
    } else {
        origin = uShadowOrigin;
        dir = normalize(uShadowRayBasis * vec3(ndc, 1.0));
    }
}

// The map's stored quantity for the plane through P with normal N, along the ray through uv.
// Where the ray grazes the plane (or meets it behind the light) the answer is `fallback`.
float receiverDistanceAt(vec2 uv, vec3 P, vec3 N, float fallback) {
    vec3 o, d;
    shadowRay(uv, o, d);
    float dn = dot(d, N);
    if (abs(dn) < 0.08) return fallback;  // beyond ~85 degrees the plane guess is worthless
    float t = dot(P - o, N) / dn;
    if (t <= 0.0) return fallback;
    return shadowDistanceOf(o + t * d);
}

// Tolerance of a depth comparison at distance d: rasterisation and rounding of 32F distances
// (relative 1e-5 at most here) are far below it; one in a thousand keeps acne off curved
// receivers whose plane guess is off by curvature x texel^2.
float receiverTolerance(float d) { return 1e-3 * d; }

// True when the map says a caster is in front of the receiver plane at texel `texel`.
bool blockedAtTexel(ivec2 texel, vec3 P, vec3 N, float dP) {
    vec2 uvCentre = (vec2(texel) + 0.5) / uShadowSize;
    float expect = receiverDistanceAt(uvCentre, P, N, dP);
    float z = texelFetch(uShadowDistance, texel, 0).r;
    return z < expect - receiverTolerance(expect);
}

ivec2 shadowTexel(vec2 uv) {
    return clamp(ivec2(floor(uv * uShadowSize)), ivec2(0), ivec2(int(uShadowSize) - 1));
}

#endif
