// How a box is read from a summed-area table: exact, since the table is bilinear inside a cell.
// SPDX-License-Identifier: GPL-3.0-or-later
// Integer corner sums are differenced before the fractional weights (float precision).
// Compiled only in the FILTER_SAT variant: the three filters share one include list.
#if defined(FILTER_SAT)
// One R32F layer per slice, so a slice is picked by index (a coordinate), not by sampler and
// channel: the shading pass can loop over only the slices that matter (combine.glsl).
uniform sampler2DArray satTables;  // layer k: slice k's (W + 1) x (H + 1) table
uniform vec2 satTexel;             // 1 / (W + 1, H + 1) (prefilter.cpp, bindFiltered)
// Per slice: (min x, min y, max x + 1, max y + 1) of its occupied texels (empty: min > max).
uniform vec4 sliceBounds[16];

// The box's corners: lo, hi in texels clamped to slice k's occupied bounds (the box's integral
// is the same: nothing lies outside them, and the table is only built inside them), their
// cells a, b and fractions.
struct SatBox {
    ivec2 a, b;
    vec2 fa, fb;
    float area;
};

SatBox satBox(int k, vec2 centre, vec2 size) {
    vec4 bounds = sliceBounds[k];
    vec2 lo = clamp(centre - 0.5 * size, bounds.xy, bounds.zw);
    vec2 hi = clamp(centre + 0.5 * size, bounds.xy, bounds.zw);
    ivec2 last = ivec2(bounds.zw) - 1;
    SatBox box;
    box.area = max(size.x * size.y, 1e-12);
    box.a = min(ivec2(floor(lo)), last);
    box.b = min(ivec2(floor(hi)), last);
    box.fa = lo - vec2(box.a);
    box.fb = hi - vec2(box.b);
    return box;
}

// textureGather at the shared corner of texels p and p + 1 returns
// (p.x, p.y+1), (p.x+1, p.y+1), (p.x+1, p.y), (p.x, p.y) as x, y, z, w.
vec3 satGatherAt(int k, ivec2 p) { return vec3((vec2(p) + 1.0) * satTexel, float(k)); }

// One row of the box: the table's integral along x from lo to hi at rows j (w, z) and j + 1 (x, y)
// of the gathered corner blocks at a and b. Integer corners are differenced first (precision).
vec2 satRows(vec4 at, vec4 bt, SatBox box) {
    float r0 = (bt.w - at.w) + box.fb.x * (bt.z - bt.w) - box.fa.x * (at.z - at.w);
    float r1 = (bt.x - at.x) + box.fb.x * (bt.y - bt.x) - box.fa.x * (at.y - at.x);
    return vec2(r0, r1);
}

float satCombine(vec2 lowRows, vec2 highRows, SatBox box) {
    float sum = (highRows.x - lowRows.x) + box.fb.y * (highRows.y - highRows.x) - box.fa.y * (lowRows.y - lowRows.x);
    return sum / box.area;
}

// The box filter of slice k from four gathers (2x2 corner blocks) instead of sixteen fetches:
// fetches dominate the shading pass on llvmpipe.
float boxFilterSlice(int k, vec2 centre, vec2 size) {
    if (sliceBounds[k].x > sliceBounds[k].z) return 0.0;  // an empty slice: no table was built
    SatBox box = satBox(k, centre, size);
    vec4 aa = textureGather(satTables, satGatherAt(k, box.a), 0);
    vec4 ba = textureGather(satTables, satGatherAt(k, ivec2(box.b.x, box.a.y)), 0);
    vec4 ab = textureGather(satTables, satGatherAt(k, ivec2(box.a.x, box.b.y)), 0);
    vec4 bb = textureGather(satTables, satGatherAt(k, box.b), 0);
    return satCombine(satRows(aa, ba, box), satRows(ab, bb, box), box);
}

// False when the box cannot reach an occupied texel of slice k: its filtered value is exactly 0.
bool boxMeetsSlice(int k, vec2 centre, vec2 size) {
    vec4 b = sliceBounds[k];
    vec2 lo = centre - 0.5 * size, hi = centre + 0.5 * size;
    return all(bvec4(lessThan(lo, b.zw), greaterThan(hi, b.xy)));
}

// The four slices of RGBA group g, as the probe reads every filter.
float boxFilterChannel0(int g, vec2 centre, vec2 size) { return boxFilterSlice(4 * g + 0, centre, size); }
float boxFilterChannel1(int g, vec2 centre, vec2 size) { return boxFilterSlice(4 * g + 1, centre, size); }
float boxFilterChannel2(int g, vec2 centre, vec2 size) { return boxFilterSlice(4 * g + 2, centre, size); }
float boxFilterChannel3(int g, vec2 centre, vec2 size) { return boxFilterSlice(4 * g + 3, centre, size); }
#endif
