// How the summed-area table's first pass runs: one invocation per table row.
// SPDX-License-Identifier: GPL-3.0-or-later
// A running sum of the slice texels to its left (row 0 and column 0 of the table stay zero).
#version 450 core
layout(local_size_x = 64) in;

uniform sampler2D slices;  // one RGBA group of occlusion textures, W x H
layout(rgba32f, binding = 0) uniform writeonly image2D table;  // (W + 1) x (H + 1)

void main() {
    ivec2 size = textureSize(slices, 0);
    int j = int(gl_GlobalInvocationID.x);
    if (j > size.y) return;
    vec4 sum = vec4(0.0);
    imageStore(table, ivec2(0, j), sum);
    for (int i = 1; i <= size.x; ++i) {
        // Binary texels: every partial sum is an integer below 2^24, exact in float.
        if (j > 0) sum += texelFetch(slices, ivec2(i - 1, j - 1), 0);
        imageStore(table, ivec2(i, j), sum);
    }
}
