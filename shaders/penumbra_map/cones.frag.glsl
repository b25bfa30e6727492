// What a cone or sheet fragment writes into the penumbra map (Wyman and Hansen, eq. 1):
// I = (Z_F - Z_V) / (Z_P - Z_V), then a light intensity, as colour and as depth so that the
// LESS depth test keeps the darkest value at every texel.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/shadow_map.glsl"

in vec3 vWorld;
in float vZv;

// 0 "coverage": the share of a disk light seen past a straight edge at the point's place across
//   the outer penumbra (V = 0.5 at the hard edge, as the truth has it);
// 1 "paper": the paper's I' = 3I^2 - 2I^3 (V = 0 at the hard edge).
uniform int uIntensityRule;

layout(location = 0) out float oIntensity;

const float kPi = 3.14159265358979;

// t is the receiver's place across the outer penumbra, 0 at the hard edge, 1 at its outer
// boundary, measured in the receiver's plane of constant depth: the penumbra there is
// L_r (Z_P - Z_V) / Z_V wide and the cone meets the texel's ray at Z_F where its radius equals
// the point's offset scaled by Z_F / Z_P, so t = I Z_P / Z_F (docs/methods/penumbra_map.md).
// The light's part still seen is the disk minus the segment beyond the edge at offset t radii.
float diskSeenPastEdge(float t) {
    float segment = acos(t) - t * sqrt(max(1.0 - t * t, 0.0));
    return 1.0 - segment / kPi;
}

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
    float intensity;
    if (uIntensityRule == 1)
        intensity = I * I * (3.0 - 2.0 * I);
    else
        intensity = diskSeenPastEdge(clamp(I * zP / max(zF, 1e-30), 0.0, 1.0));
    oIntensity = intensity;
    gl_FragDepth = intensity;
}
