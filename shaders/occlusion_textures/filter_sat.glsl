// How a box is read from a summed-area table: exact, since the table is bilinear inside a cell.
// SPDX-License-Identifier: GPL-3.0-or-later
// Integer corner sums are differenced before the fractional weights (float precision).
// Compiled only in the FILTER_SAT variant: the three filters share one include list.
#if defined(FILTER_SAT)
uniform sampler2D filtered[4];  // per RGBA group: (W + 1) x (H + 1) RGBA32F table

vec4 satF(int g, ivec2 p, ivec2 maxP) { return texelFetch(filtered[g], clamp(p, ivec2(0), maxP), 0); }

vec4 boxFilter(int g, vec2 centre, vec2 size) {
    ivec2 tex = textureSize(filtered[g], 0) - 1;  // W, H
    vec2 lo = clamp(centre - 0.5 * size, vec2(0.0), vec2(tex));
    vec2 hi = clamp(centre + 0.5 * size, vec2(0.0), vec2(tex));
    float area = max(size.x * size.y, 1e-12);
    ivec2 a = min(ivec2(floor(lo)), tex - 1), b = min(ivec2(floor(hi)), tex - 1);
    vec2 fa = lo - vec2(a), fb = hi - vec2(b);
    vec4 strip[4];
    int rows[4] = int[4](a.y, a.y + 1, b.y, b.y + 1);
    for (int r = 0; r < 4; ++r) {
        int j = rows[r];
        vec4 fa0 = satF(g, ivec2(a.x, j), tex), fa1 = satF(g, ivec2(a.x + 1, j), tex);
        vec4 fb0 = satF(g, ivec2(b.x, j), tex), fb1 = satF(g, ivec2(b.x + 1, j), tex);
        strip[r] = (fb0 - fa0) + fb.x * (fb1 - fb0) - fa.x * (fa1 - fa0);
    }
    vec4 sum = (strip[2] - strip[0]) + fb.y * (strip[3] - strip[2]) - fa.y * (strip[1] - strip[0]);
    return sum / area;
}
#endif
