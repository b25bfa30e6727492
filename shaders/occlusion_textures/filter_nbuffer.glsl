// How a box is read from N-Buffers: the two levels bracketing the short side.
// SPDX-License-Identifier: GPL-3.0-or-later
// Linear in the size between them; a rectangle averages square lookups along its long side (mirrors
// filters/).
// Compiled only in the FILTER_NBUFFER variant: the three filters share one include list.
#if defined(FILTER_NBUFFER)
uniform sampler2DArray filtered[4];  // per RGBA group: layer l = mean of the 2^l box (RGBA16F)

// One channel of level l, bilinear at `centre` (texels of level 0), from one textureGather
// (layer = level): llvmpipe's filtered path is several times slower than plain reads, and its
// 8-bit weights would be coarser. Outside the texture the border is 0 (CLAMP_TO_BORDER).
// textureGather needs its component as a literal, hence one set of functions per channel.
#define SS_NBUFFER_CHANNEL(C)                                                                  \
    float nbufferLevel##C(int g, int level, vec2 centre) {                                     \
        float half_ = 0.5 * float(1 << level);                                                 \
        /* Texel i of level l averages [i, i + 2^l): its box is centred at i + 2^(l-1). */     \
        vec2 f = centre - half_;                                                               \
        vec2 i = floor(f), w = f - i;                                                          \
        vec2 size = vec2(textureSize(filtered[g], 0).xy);                                      \
        /* x, y, z, w = (i, i+1), (i+1, i+1), (i+1, i), (i, i) */                              \
        vec4 q = textureGather(filtered[g], vec3((i + 1.0) / size, float(level)), C);          \
        return mix(mix(q.w, q.z, w.x), mix(q.x, q.y, w.x), w.y);                               \
    }                                                                                          \
    float nbufferSquare##C(int g, vec2 centre, float s) {                                      \
        int top = textureSize(filtered[g], 0).z - 1;                                           \
        int l = min(int(floor(log2(max(s, 1.0)))), top);                                       \
        if (l >= top) return nbufferLevel##C(g, top, centre);                                  \
        float size = float(1 << l);                                                            \
        float t = clamp((s - size) / size, 0.0, 1.0);                                          \
        return mix(nbufferLevel##C(g, l, centre), nbufferLevel##C(g, l + 1, centre), t);       \
    }                                                                                          \
    float boxFilterChannel##C(int g, vec2 centre, vec2 size) {                                 \
        float s = min(size.x, size.y), L = max(size.x, size.y);                                \
        int probes = clamp(int(ceil(L / max(s, 1e-6) - 1e-3)), 1, 8);                          \
        vec2 axis = size.x >= size.y ? vec2(1.0, 0.0) : vec2(0.0, 1.0);                        \
        float sum = 0.0;                                                                       \
        for (int k = 0; k < probes; ++k) {                                                     \
            float offset = (float(k) + 0.5) * L / float(probes) - 0.5 * L;                     \
            sum += nbufferSquare##C(g, centre + offset * axis, s);                             \
        }                                                                                      \
        return sum / float(probes);                                                            \
    }
SS_NBUFFER_CHANNEL(0)
SS_NBUFFER_CHANNEL(1)
SS_NBUFFER_CHANNEL(2)
SS_NBUFFER_CHANNEL(3)
#endif
