// How a box is read from N-Buffers: the two levels bracketing the short side, linear in the size
// between them; a rectangle averages square lookups along its long side (mirrors filters/).
// SPDX-License-Identifier: GPL-3.0-or-later
// Compiled only in the FILTER_NBUFFER variant: the three filters share one include list.
#if defined(FILTER_NBUFFER)
uniform sampler2DArray filtered[4];  // per RGBA group: layer l = mean of the 2^l box (RGBA16F)

vec4 nbufferLevel(int g, int level, vec2 centre) {
    vec2 size = vec2(textureSize(filtered[g], 0).xy);
    float half_ = 0.5 * float(1 << level);
    // Texel i of level l averages [i, i + 2^l): its box is centred at i + 2^(l-1).
    return texture(filtered[g], vec3((centre - half_ + 0.5) / size, float(level)));
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
#endif
