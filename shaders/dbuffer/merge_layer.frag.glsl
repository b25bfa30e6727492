// How one layer of parts joins the D-buffer: its texel's volume distance and silhouette distance
// (one part's, by the rule within a part) compete by depth with the other layers' (the rule
// across parts, methods/dbuffer/method.cpp); the colour mask picks the umbra or penumbra pair.
// SPDX-License-Identifier: GPL-3.0-or-later
uniform sampler2D uLayer;  // R |cx_uv|, G |cx_s| of the layer (0 = no exit drawn)
uniform float uFar;        // the volume pass's distance scale

layout(location = 0) out vec4 oDistances;

void main() {
    vec2 layer = texelFetch(uLayer, ivec2(gl_FragCoord.xy), 0).rg;
    if (!(layer.x > 0.0)) discard;
    gl_FragDepth = clamp(layer.x / uFar, 0.0, 1.0);
    oDistances = vec4(layer, layer);
}
