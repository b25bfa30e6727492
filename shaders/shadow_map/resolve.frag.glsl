// How the hard shadow from the light centre is decided per camera pixel (the shadow_map method).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/camera_gbuffer.glsl"
#include "common/visibility_contract.glsl"
#include "common/shadow_map.glsl"
#include "common/unseen_centre.glsl"

// Bias in texel footprints (methods/shadow_map.cpp explains the numbers).
uniform float uConstantBias;
uniform float uSlopeBias;

layout(location = 0) out vec4 oResult;  // V, mask, distance to the light, 0

void main() {
    Surface s = loadSurface(ivec2(gl_FragCoord.xy));
    float d = s.covered ? shadowDistanceOf(s.position) : 0.0;
    if (!s.receives || !lightReaches(s.position, s.normal)) {
        oResult = vec4(1.0, 0.0, d, 0.0);
        return;
    }
    float V;
    vec2 uv;
    vec3 toLight = uShadowOrthographic != 0 ? -uShadowAxis : normalize(uShadowOrigin - s.position);
    vec3 P = shadowLookupPoint(s.position, s.normal, toLight);
    bool belowHorizon = belowHorizonDecides(s.position, s.normal, toLight, V);
    if (!belowHorizon && shadowMapUv(P, uv)) {
        ivec2 texel = clamp(ivec2(uv * uShadowSize), ivec2(0), ivec2(int(uShadowSize) - 1));
        float stored = texelFetch(uShadowDistance, texel, 0).r;
        d = shadowDistanceOf(P);
        float cosT = max(abs(dot(s.normal, toLight)), 0.05);
        float tanT = min(sqrt(max(1.0 - cosT * cosT, 0.0)) / cosT, 20.0);
        float bias = shadowTexelWorldSize(d) * (uConstantBias + uSlopeBias * tanT);
        V = stored < d - bias ? 0.0 : 1.0;
    }
    oResult = vec4(V, 1.0, shadowDistanceOf(s.position), 0.0);
}
