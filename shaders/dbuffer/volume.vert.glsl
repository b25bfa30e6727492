// How a volume vertex reaches the light-centre view, carrying its silhouette edge for eq. 2.
// SPDX-License-Identifier: GPL-3.0-or-later
layout(location = 0) in vec3 aPosition;   // world space
layout(location = 1) in vec3 aEdgeA;      // the silhouette edge this triangle was extruded from
layout(location = 2) in vec3 aEdgeB;
layout(location = 3) in vec3 aExtrusion;  // its extrusion point (silhouette face: its normal)
layout(location = 4) in float aKind;      // ss::VolumeKind

uniform mat4 uWorldToClip;  // the shared shadow map's view: D-buffer texels match its texels

out vec3 vWorld;
flat out vec3 vEdgeA;
flat out vec3 vEdgeB;
flat out vec3 vExtrusion;
flat out int vKind;

void main() {
    vWorld = aPosition;
    vEdgeA = aEdgeA;
    vEdgeB = aEdgeB;
    vExtrusion = aExtrusion;
    vKind = int(aKind + 0.5);
    gl_Position = uWorldToClip * vec4(aPosition, 1.0);
}
