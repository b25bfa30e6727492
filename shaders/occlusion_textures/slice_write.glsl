// How a fragment marks its slice's occlusion: one channel per slice, four slices per target.
// SPDX-License-Identifier: GPL-3.0-or-later
in float lightDepth;

uniform float firstPlane;  // depth of the first slice's upper plane
uniform float thickness;   // every slice has the same thickness
uniform int sliceCount;
uniform int thinFix;       // 1: also fill the next slice (closes leaks of thin occluders)

// Blended with GL_MAX: a texel holds the most any fragment of its slice covers it.
layout(location = 0) out vec4 group0;
layout(location = 1) out vec4 group1;
layout(location = 2) out vec4 group2;
layout(location = 3) out vec4 group3;

void writeSlice(float occlusion) {
    int k = clamp(int(floor((lightDepth - firstPlane) / thickness)), 0, sliceCount - 1);
    vec4 o[4] = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    o[k / 4][k % 4] = occlusion;
    if (thinFix != 0 && k + 1 < sliceCount) o[(k + 1) / 4][(k + 1) % 4] = occlusion;
    group0 = o[0];
    group1 = o[1];
    group2 = o[2];
    group3 = o[3];
}
