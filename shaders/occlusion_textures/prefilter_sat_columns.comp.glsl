// How the summed-area table's second pass runs: one invocation per table column of one group.
// SPDX-License-Identifier: GPL-3.0-or-later
// A running sum downwards over the first pass's row sums, each channel into its slice's layer.
#version 450 core
layout(local_size_x = 64) in;

uniform int firstSlice;  // 4 * group
uniform int sliceCount;  // the table's layers
layout(rgba32f, binding = 0) uniform readonly image2D rowSums;
layout(r32f, binding = 1) uniform writeonly image2DArray table;  // (W + 1) x (H + 1) x sliceCount

void main() {
    ivec2 size = imageSize(rowSums);
    int i = int(gl_GlobalInvocationID.x);
    if (i >= size.x) return;
    int channels = min(4, sliceCount - firstSlice);
    vec4 sum = vec4(0.0);
    for (int j = 0; j < size.y; ++j) {
        sum += imageLoad(rowSums, ivec2(i, j));
        for (int c = 0; c < channels; ++c) imageStore(table, ivec3(i, j, firstSlice + c), vec4(sum[c]));
    }
}
