// How penumbra_map shades a camera pixel (pass 3): inside the hard shadow from the light centre
// V = 0, elsewhere V is the penumbra map's value at the point's shadow-map texel.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/camera_gbuffer.glsl"
#include "common/visibility_contract.glsl"
#include "pcss/receiver_plane.glsl"

uniform sampler2D uPenumbraMap;  // R32F, same texel grid as the shadow map

// The penumbra map where P falls. Right at the hard edge P's own texel can hold the occluder
// (the texel is larger than the edge's offset; the hard test, from the normal-offset point,
// still finds P lit): no cone fragment survives there, it reads 1 and would draw a lit seam along
// the hard shadow. Then the darkest of the eight neighbours is the ramp's start.
float penumbraAt(vec3 P, ivec2 texel) {
    float pm = texelFetch(uPenumbraMap, texel, 0).r;
    bool ownTexelOccluded = texelFetch(uShadowDistance, texel, 0).r < shadowDistanceOf(P) * (1.0 - 1e-3);
    if (pm < 1.0 || !ownTexelOccluded) return pm;
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
    if (!inMap || !shadowMapUv(P, uvP)) return;
    float dP = shadowDistanceOf(P);
    if (blockedAtTexel(receiverPlane(P, s.normal), shadowTexel(uvP), dP)) {
        oResult.x = 0.0;
        oResult.z = 1.0;
        return;
    }
    oResult.x = pm;
}
