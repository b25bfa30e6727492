// How a box is read from a summed-area table: exact, since the table is bilinear inside a cell.
// SPDX-License-Identifier: GPL-3.0-or-later
// Integer corner sums are differenced before the fractional weights (float precision).
// Compiled only in the FILTER_SAT variant: the three filters share one include list.
#if defined(FILTER_SAT)
uniform sampler2D filtered[4];  // per RGBA group: (W + 1) x (H + 1) RGBA32F table

// The box's corners: lo, hi in texels clamped to the table, their cells a, b and fractions.
struct SatBox {
    ivec2 a, b;
    vec2 fa, fb;
    float area;
};

SatBox satBox(int g, vec2 centre, vec2 size) {
    ivec2 tex = textureSize(filtered[g], 0) - 1;  // W, H
    vec2 lo = clamp(centre - 0.5 * size, vec2(0.0), vec2(tex));
    vec2 hi = clamp(centre + 0.5 * size, vec2(0.0), vec2(tex));
    SatBox box;
    box.area = max(size.x * size.y, 1e-12);
    box.a = min(ivec2(floor(lo)), tex - 1);
    box.b = min(ivec2(floor(hi)), tex - 1);
    box.fa = lo - vec2(box.a);
    box.fb = hi - vec2(box.b);
    return box;
}

// textureGather at the shared corner of texels p and p + 1 returns, for one channel,
// (p.x, p.y+1), (p.x+1, p.y+1), (p.x+1, p.y), (p.x, p.y) as x, y, z, w.
vec2 satGatherAt(int g, ivec2 p) { return (vec2(p) + 1.0) / vec2(textureSize(filtered[g], 0)); }

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

// One channel of the box filter from four gathers (2x2 corner blocks) instead of sixteen RGBA
// fetches: fetches dominate the shading pass on llvmpipe. textureGather needs its component as a
// literal, hence one function per channel.
#define SS_SAT_BOX_CHANNEL(C)                                                                   \
    float boxFilterChannel##C(int g, vec2 centre, vec2 size) {                                  \
        SatBox box = satBox(g, centre, size);                                                   \
        vec4 aa = textureGather(filtered[g], satGatherAt(g, box.a), C);                         \
        vec4 ba = textureGather(filtered[g], satGatherAt(g, ivec2(box.b.x, box.a.y)), C);       \
        vec4 ab = textureGather(filtered[g], satGatherAt(g, ivec2(box.a.x, box.b.y)), C);       \
        vec4 bb = textureGather(filtered[g], satGatherAt(g, box.b), C);                         \
        return satCombine(satRows(aa, ba, box), satRows(ab, bb, box), box);                     \
    }
SS_SAT_BOX_CHANNEL(0)
SS_SAT_BOX_CHANNEL(1)
SS_SAT_BOX_CHANNEL(2)
SS_SAT_BOX_CHANNEL(3)
#endif
