// How a box is read from N-Buffers: the two levels bracketing the short side.
// SPDX-License-Identifier: GPL-3.0-or-later
// Linear in the size between them; a rectangle averages square lookups along its long side (mirrors
// filters/).
// Compiled only in the FILTER_NBUFFER variant: the three filters share one include list.
#if defined(FILTER_NBUFFER)
uniform sampler2DArray filtered[4];  // per RGBA group: layer l = mean of the 2^l box (RGBA16F)

// Bilinear from four texel fetches (outside: 0): llvmpipe's filtered path is several times
// slower than plain fetches, and its 8-bit weights would be coarser.
vec4 nbufferTexel(int g, ivec2 p, int level) {
    ivec2 size = textureSize(filtered[g], 0).xy;
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) return vec4(0.0);
    return texelFetch(filtered[g], ivec3(p, level), 0);
}

vec4 nbufferLevel(int g, int level, vec2 centre) {
    float half_ = 0.5 * float(1 << level);
    // Texel i of level l averages [i, i + 2^l): its box is centred at i + 2^(l-1).
    vec2 f = centre - half_;
    ivec2 i = ivec2(floor(f));
    vec2 w = f - vec2(i);
    return mix(mix(nbufferTexel(g, i, level), nbufferTexel(g, i + ivec2(1, 0), level), w.x),
               mix(nbufferTexel(g, i + ivec2(0, 1), level), nbufferTexel(g, i + ivec2(1, 1), level), w.x), w.y);
}

vec4 nbufferSquare(int g, vec2 centre, float s) {
    int top = textureSize(filtered[g], 0).z - 1;
    int l = min(int(floor(log2(max(s, 1.0)))), top);
    if (l >= top) return nbufferLevel(g, top, centre);
    float size = float(1 << l);
    float t = clamp((s - size) / size, 0.0, 1.0);
    return mix(nbufferLevel(g, l, centre), nbufferLevel(g, l + 1, centre), t);
}

vec4 boxFilter(int g, vec2 centre, vec2 size) {
    float s = min(size.x, size.y), L = max(size.x, size.y);
    int probes = clamp(int(ceil(L / max(s, 1e-6) - 1e-3)), 1, 8);
    vec2 axis = size.x >= size.y ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    vec4 sum = vec4(0.0);
    for (int k = 0; k < probes; ++k) {
        float offset = (float(k) + 0.5) * L / float(probes) - 0.5 * L;
        sum += nbufferSquare(g, centre + offset * axis, s);
    }
    return sum / float(probes);
}
// One channel, as the combination reads it (the SAT variant gathers that channel only).
float boxFilterChannel0(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).x; }
float boxFilterChannel1(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).y; }
float boxFilterChannel2(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).z; }
float boxFilterChannel3(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).w; }
#endif
