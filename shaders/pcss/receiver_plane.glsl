// What distance the shadow map would store at a texel if the receiver were the plane (P, N):
// the depth comparison pcss and penumbra_map use instead of a constant bias.
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_PCSS_RECEIVER_PLANE_GLSL
#define SS_PCSS_RECEIVER_PLANE_GLSL
#include "common/shadow_map.glsl"

// Columns: the map's right and up axes scaled by tan(half fov) (perspective) or by the half
// width (orthographic), then its unit view axis. Set by shadowRayBasis() on the C++ side.
uniform mat3 uShadowRayBasis;

// The plane through a receiver point with its normal, prepared so that the distance along any
// texel's light ray costs a few multiply-adds (no normalize, no matrix): with the ray basis
// columns B0 = s right, B1 = s up, B2 = axis, the ray through ndc (x, y) is B (x, y, 1)
// (perspective, from the origin) or origin + B (x, y, 0) along the axis (orthographic).
struct ReceiverPlane {
    float k;        // dot(P - origin, N)
    vec3 dots;      // dot(B0, N), dot(B1, N), dot(B2, N)
    float scale2;   // s^2 (perspective)
};

ReceiverPlane receiverPlane(vec3 P, vec3 N) {
    ReceiverPlane rp;
    rp.k = dot(P - uShadowOrigin, N);
    rp.dots = vec3(dot(uShadowRayBasis[0], N), dot(uShadowRayBasis[1], N), dot(uShadowRayBasis[2], N));
    rp.scale2 = dot(uShadowRayBasis[0], uShadowRayBasis[0]);
    return rp;
}

// Relative tolerance of a depth comparison: rasterisation and rounding of 32F distances
// (relative 1e-5 at most here) are far below it; one in a thousand keeps acne off curved
// receivers whose plane guess is off by curvature x texel^2.
const float kReceiverTolerance = 1e-3;

// True when the map's quantity z at `texel` is in front of the receiver plane (on the side its
// normal points to, where the light P receives comes from). A ray through the texel's centre
// that starts in front of the plane (the light centre above P's horizon) is in front until it
// meets the plane: z must be below the plane's quantity along it, less the tolerance. Where that
// ray grazes the plane (beyond ~85 degrees) the plane is taken as tilted no further than that:
// the exact quantity runs to infinity there and makes a curved receiver's own neighbouring facets
// shadow it (acne along terminators). A ray that starts behind the plane (the centre on or below
// P's horizon) is in front only beyond the point where it crosses the plane: z must be above the
// plane's quantity, plus the tolerance, and below P's own dP (nearer the light than P: the ground
// beyond a curved caster's rim is in front of the plane too, but farther); a ray that never
// crosses holds nothing in front. Without
// that, a lit caster's faces that see part of the light but not its centre read their own mesh
// as a blocker (tests/native/test_lit_caster_faces.cpp). Along the ray B (x, y, 1)
// (perspective) the plane's quantity is k |B (x, y, 1)| / (B (x, y, 1)).N; along the axis from
// origin + B (x, y, 0) (orthographic) it is (k - x B0.N - y B1.N) / B2.N. The comparisons are
// multiplied out by the denominators: pcss runs this for every kernel sample.
bool inFrontOfReceiver(ReceiverPlane rp, ivec2 texel, float z, float dP) {
    vec2 ndc = (vec2(texel) + 0.5) * (2.0 / uShadowSize) - 1.0;
    const float keep = 1.0 - kReceiverTolerance;
    if (uShadowOrthographic != 0) {
        float num = rp.k - rp.dots.x * ndc.x - rp.dots.y * ndc.y;
        if (num < 0.0) return z * min(rp.dots.z, -0.08) > keep * num;
        return rp.dots.z > 0.0 && z < keep * dP && keep * z * rp.dots.z > num;
    }
    float len = sqrt(rp.scale2 * dot(ndc, ndc) + 1.0);
    float dn = rp.dots.x * ndc.x + rp.dots.y * ndc.y + rp.dots.z;
    if (rp.k < 0.0) return z * min(dn, -0.08 * len) > keep * rp.k * len;
    return dn > 0.0 && z < keep * dP && keep * z * dn > rp.k * len;
}

// True when the map says a caster is in front of the receiver plane at texel `texel`.
bool blockedAtTexel(ReceiverPlane rp, ivec2 texel, float dP) {
    return inFrontOfReceiver(rp, texel, texelFetch(uShadowDistance, texel, 0).r, dP);
}

ivec2 shadowTexel(vec2 uv) {
    return clamp(ivec2(floor(uv * uShadowSize)), ivec2(0), ivec2(int(uShadowSize) - 1));
}

#endif
