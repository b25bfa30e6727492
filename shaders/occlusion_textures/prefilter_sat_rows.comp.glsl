// How the summed-area table's first pass runs: one invocation per table row of one RGBA group.
// SPDX-License-Identifier: GPL-3.0-or-later
// A running sum of the slice texels to its left (row 0 and column 0 of the table stay zero),
// four slices at once. The same scan records each slice's occupied texels, so shading can skip
// a slice wherever the kernel misses them (combine.glsl).
#version 450 core
layout(local_size_x = 64) in;

uniform sampler2D slices;  // one RGBA group of occlusion textures, W x H
uniform int firstSlice;    // 4 * group: channel c is slice firstSlice + c
uniform int sliceCount;    // slices in all (a last group may use fewer than four channels)
layout(rgba32f, binding = 0) uniform writeonly image2D rowSums;  // (W + 1) x (H + 1)
// Per slice: min x, min y, max x, max y of its occupied texels (empty: min > max).
layout(std430, binding = 2) buffer SliceBounds { int bounds[]; };

void main() {
    ivec2 size = textureSize(slices, 0);
    int j = int(gl_GlobalInvocationID.x);
    if (j > size.y) return;
    vec4 sum = vec4(0.0);
    ivec4 first = ivec4(size.x), last = ivec4(-1);
    imageStore(rowSums, ivec2(0, j), sum);
    for (int i = 1; i <= size.x; ++i) {
        if (j > 0) {
            // Binary texels: every partial sum is an integer below 2^24, exact in float.
            vec4 t = texelFetch(slices, ivec2(i - 1, j - 1), 0);
            sum += t;
            bvec4 on = greaterThan(t, vec4(0.0));
            first = mix(first, min(first, ivec4(i - 1)), on);
            last = mix(last, ivec4(i - 1), on);
        }
        imageStore(rowSums, ivec2(i, j), sum);
    }
    for (int c = 0; c < min(4, sliceCount - firstSlice); ++c) {
        if (last[c] < 0) continue;
        int k = 4 * (firstSlice + c);
        atomicMin(bounds[k + 0], first[c]);
        atomicMin(bounds[k + 1], j - 1);
        atomicMax(bounds[k + 2], last[c]);
        atomicMax(bounds[k + 3], j - 1);
    }
}
