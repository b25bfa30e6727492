// How the summed-area table's second pass runs: one invocation per table column.
// SPDX-License-Identifier: GPL-3.0-or-later
// A running sum downwards over the row sums written by the first pass.
#version 450 core
layout(local_size_x = 64) in;

layout(rgba32f, binding = 0) uniform image2D table;

void main() {
    ivec2 size = imageSize(table);
    int i = int(gl_GlobalInvocationID.x);
    if (i >= size.x) return;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < size.y; ++j) {
        sum += imageLoad(table, ivec2(i, j));
        imageStore(table, ivec2(i, j), sum);
    }
}
