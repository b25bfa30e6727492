// How the summed-area table's second pass runs: one invocation per table column of one group.
// SPDX-License-Identifier: GPL-3.0-or-later
// A running sum downwards over the first pass's row sums, each channel into its slice's layer.
// Only inside the group's occupied bounds: elsewhere the table is 0 or repeats its edge, and
// lookups clamp their boxes to each slice's bounds (filter_sat.glsl), so nothing reads it.
#version 450 core
#include "occlusion_textures/slice_bounds.glsl"
layout(local_size_x = 64) in;

layout(rgba32f, binding = 0) uniform readonly image2D rowSums;
layout(r32f, binding = 1) uniform writeonly image2DArray table;  // (W + 1) x (H + 1) x sliceCount

void main() {
    int channels = min(4, sliceCount - firstSlice);
    // The union of the group's bounds, in table coordinates: texels x0..x1 are columns x0..x1+1.
    ivec2 lo = ivec2(0x7fffffff), hi = ivec2(-1);
    for (int c = 0; c < channels; ++c) {
        int k = 4 * (firstSlice + c);
        lo = min(lo, ivec2(bounds[k], bounds[k + 1]));
        hi = max(hi, ivec2(bounds[k + 2], bounds[k + 3]));
    }
    int i = int(gl_GlobalInvocationID.x);
    if (i < lo.x || i > hi.x + 1) return;
    vec4 sum = vec4(0.0);
    for (int j = lo.y; j <= hi.y + 1; ++j) {
        sum += imageLoad(rowSums, ivec2(i, j));
        for (int c = 0; c < channels; ++c) imageStore(table, ivec3(i, j, firstSlice + c), vec4(sum[c]));
    }
}
