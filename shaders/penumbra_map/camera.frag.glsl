// How penumbra_map shades a camera pixel (pass 3): inside the hard shadow from the light centre
// V = 0, elsewhere V is the penumbra map's value at the point's shadow-map texel.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/camera_gbuffer.glsl"
#include "common/visibility_contract.glsl"
#include "pcss/receiver_plane.glsl"

uniform sampler2D uPenumbraMap;  // R32F, same texel grid as the shadow map

layout(location = 0) out vec4 oResult;  // V, mask, hard shadow (0/1), penumbra map value

void main() {
    Surface s = loadSurface(ivec2(gl_FragCoord.xy));
    oResult = vec4(1.0, 0.0, 0.0, 1.0);
    if (!s.covered) return;
    vec2 uv;
    bool inMap = shadowMapUv(s.position, uv);
    ivec2 texel = shadowTexel(uv);
    float pm = inMap ? texelFetch(uPenumbraMap, texel, 0).r : 1.0;
    oResult.w = pm;
    if (!s.receives || !lightReaches(s.position, s.normal)) return;
    oResult.y = 1.0;
    if (!inMap) return;
    float dP = shadowDistanceOf(s.position);
    if (blockedAtTexel(receiverPlane(s.position, s.normal), texel, dP)) {
        oResult.x = 0.0;
        oResult.z = 1.0;
        return;
    }
    oResult.x = pm;
}
