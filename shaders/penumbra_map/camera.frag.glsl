// How penumbra_map shades a camera pixel (pass 3): inside the hard shadow from the light centre
// V = 0, elsewhere V is the penumbra map's value at the point's shadow-map texel.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/camera_gbuffer.glsl"
#include "common/visibility_contract.glsl"
#include "pcss/receiver_plane.glsl"
#include "common/unseen_centre.glsl"

uniform sampler2D uPenumbraMap;  // R32F, same texel grid as the shadow map

// The penumbra map where P falls, when P's own texel holds P's own surface. Along a silhouette
// the texel can hold another surface, one more than 10 % nearer or farther from the light (within
// that, it is P's own surface, sampled at the texel's centre; grazing surfaces vary that much):
// - the occluder, right at the hard edge (the texel is wider than P's offset from the edge; the
//   hard test, from the normal-offset point, still finds P lit). No cone fragment survives over
//   it, it reads 1 and drew a lit seam along every hard shadow: the darkest of the eight
//   neighbours, the ramp's start, is used instead;
// - a surface behind P, when P is on an occluder's own rim (a curved occluder at its terminator,
//   seen from the light): the value is that surface's penumbra, which starts right there, and
//   painted the rim with the ramp's start. P is in front of that surface and its ramp: lit.
float penumbraAt(vec3 P, ivec2 texel) {
    float pm = texelFetch(uPenumbraMap, texel, 0).r;
    float stored = texelFetch(uShadowDistance, texel, 0).r, own = shadowDistanceOf(P);
    if (stored > own * 1.1) return 1.0;
    if (pm < 1.0 || stored >= own * 0.9) return pm;
    ivec2 last = textureSize(uPenumbraMap, 0) - 1;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) pm = min(pm, texelFetch(uPenumbraMap, clamp(texel + ivec2(dx, dy), ivec2(0), last), 0).r);
    return pm;
}

layout(location = 0) out vec4 oResult;  // V, mask, hard shadow (0/1), penumbra map value

void main() {
    Surface s = loadSurface(ivec2(gl_FragCoord.xy));
    oResult = vec4(1.0, 0.0, 0.0, 1.0);
    if (!s.covered) return;
    // The penumbra map is read where the point itself falls (its texel holds the point's own
    // surface); the hard-shadow test uses the normal-offset point against acne.
    vec2 uv;
    bool inMap = shadowMapUv(s.position, uv);
    float pm = inMap ? penumbraAt(s.position, shadowTexel(uv)) : 1.0;
    oResult.w = pm;
    if (!s.receives || !lightReaches(s.position, s.normal)) return;
    oResult.y = 1.0;
    vec3 toLight = uShadowOrthographic != 0 ? -uShadowAxis : normalize(uShadowOrigin - s.position);
    vec3 P = shadowLookupPoint(s.position, s.normal, toLight);
    vec2 uvP;
    // The map's texels at P hold P's own mesh seen from behind P's plane, and the penumbra map's
    // value is that surface's, not P's: the march towards the light P sees decides, lit or not.
    float visible;
    if (belowHorizonDecides(s.position, s.normal, toLight, visible)) {
        oResult.x = visible;
        oResult.z = 1.0 - visible;  // hard shadow
        return;
    }
    if (!inMap || !shadowMapUv(P, uvP)) return;
    float dP = shadowDistanceOf(P);
    if (blockedAtTexel(receiverPlane(P, s.normal), shadowTexel(uvP), dP)) {
        oResult.x = 0.0;
        oResult.z = 1.0;
        return;
    }
    oResult.x = pm;
}
