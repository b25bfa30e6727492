// How a compute pass records each slice's occupied texels while it scans one row of an RGBA group.
// SPDX-License-Identifier: GPL-3.0-or-later
// Shading skips a slice (and a pixel) wherever the kernel misses them (combine.glsl). Used by the
// SAT row pass and, for the other filters, by prefilter_bounds.comp.glsl.
uniform int firstSlice;  // 4 * group: channel c is slice firstSlice + c
uniform int sliceCount;  // slices in all (a last group may use fewer than four channels)
// Per slice: min x, min y, max x, max y of its occupied texels (empty: min > max).
layout(std430, binding = 2) buffer SliceBounds { int bounds[]; };

struct RowSpan {
    ivec4 first, last;  // per channel: the first and last occupied x of the row (none: last < 0)
};

RowSpan emptyRowSpan(int width) {
    RowSpan r;
    r.first = ivec4(width);
    r.last = ivec4(-1);
    return r;
}

void addTexel(inout RowSpan r, int x, vec4 texel) {
    bvec4 on = greaterThan(texel, vec4(0.0));
    r.first = mix(r.first, min(r.first, ivec4(x)), on);
    r.last = mix(r.last, ivec4(x), on);
}

void recordRow(RowSpan r, int y) {
    for (int c = 0; c < min(4, sliceCount - firstSlice); ++c) {
        if (r.last[c] < 0) continue;
        int k = 4 * (firstSlice + c);
        atomicMin(bounds[k + 0], r.first[c]);
        atomicMin(bounds[k + 1], y);
        atomicMax(bounds[k + 2], r.last[c]);
        atomicMax(bounds[k + 3], y);
    }
}
