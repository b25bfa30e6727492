// What a cone or sheet fragment writes into the penumbra map (Wyman and Hansen, eq. 1):
// I = (Z_F - Z_V) / (Z_P - Z_V) smoothed to 3I^2 - 2I^3, as colour and as depth so that the
// LESS depth test keeps the darkest value at every texel.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/shadow_map.glsl"

in vec3 vWorld;
in float vZv;

layout(location = 0) out float oIntensity;

void main() {
    float zpDistance = texelFetch(uShadowDistance, ivec2(gl_FragCoord.xy), 0).r;
    // No caster at this texel: no surface to shade here, and no known Z_P.
    if (zpDistance >= 1e29) discard;
    float fDistance = length(vWorld - uShadowOrigin);
    // Behind the shadow-map surface: this part of the cone is inside the occluder or beyond
    // the receiver.
    if (fDistance > zpDistance) discard;
    // World-space depths along the light axis. F and P lie on one ray from the light centre,
    // so P's depth is its distance scaled by F's depth/distance ratio.
    float zF = dot(vWorld - uShadowOrigin, uShadowAxis);
    float zP = zpDistance * zF / max(fDistance, 1e-30);
    float span = zP - vZv;
    if (span <= 0.0) discard;  // the receiver is not behind the silhouette point
    float I = clamp((zF - vZv) / span, 0.0, 1.0);
    I = I * I * (3.0 - 2.0 * I);
    oIntensity = I;
    gl_FragDepth = I;
}
