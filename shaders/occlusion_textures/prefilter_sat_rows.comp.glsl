// How the summed-area table's first pass runs: one invocation per table row of one RGBA group.
// SPDX-License-Identifier: GPL-3.0-or-later
// A running sum of the slice texels to its left (row 0 and column 0 of the table stay zero),
// four slices at once. The same scan records each slice's occupied texels.
#version 450 core
#include "occlusion_textures/slice_bounds.glsl"
layout(local_size_x = 64) in;

uniform sampler2D slices;  // one RGBA group of occlusion textures, W x H
layout(rgba32f, binding = 0) uniform writeonly image2D rowSums;  // (W + 1) x (H + 1)

void main() {
    ivec2 size = textureSize(slices, 0);
    int j = int(gl_GlobalInvocationID.x);
    if (j > size.y) return;
    vec4 sum = vec4(0.0);
    RowSpan row = emptyRowSpan(size.x);
    imageStore(rowSums, ivec2(0, j), sum);
    for (int i = 1; i <= size.x; ++i) {
        if (j > 0) {
            // Binary texels: every partial sum is an integer below 2^24, exact in float.
            vec4 t = texelFetch(slices, ivec2(i - 1, j - 1), 0);
            sum += t;
            addTexel(row, i - 1, t);
        }
        imageStore(rowSums, ivec2(i, j), sum);
    }
    recordRow(row, j - 1);
}
