// How a cone or sheet vertex reaches the light's clip space, carrying Z_V (its silhouette
// point's depth along the light axis).
// SPDX-License-Identifier: GPL-3.0-or-later
layout(location = 0) in vec4 aPositionZv;  // xyz world, w = Z_V

uniform mat4 uShadowWorldToClip;

out vec3 vWorld;
out float vZv;

void main() {
    vWorld = aPositionZv.xyz;
    vZv = aPositionZv.w;
    gl_Position = uShadowWorldToClip * vec4(aPositionZv.xyz, 1.0);
}
