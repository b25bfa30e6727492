// How a box is read from mipmaps: trilinear lookups at the level of the kernel's short side.
// SPDX-License-Identifier: GPL-3.0-or-later
// Spread along its long side (anisotropic filtering done here, mirrors filters/box_filter.cpp:
// llvmpipe's own GL_TEXTURE_MAX_ANISOTROPY path measured 4x further from the exact box).
// Trilinear is rebuilt from texelFetch: llvmpipe's filtered textureLod of these RGBA16F mipmaps
// cost 4x more (16 slices at 1024²: 2.25 s against 0.56 s). Level sizes are computed from level
// 0's: textureSize(sampler, level > 0) on this sampler array gave wrong sizes here, which made an
// earlier attempt read the wrong texels (the GL filter test caught it).
// Compiled only in the FILTER_MIPMAP variant: the three filters share one include list.
#if defined(FILTER_MIPMAP)
uniform sampler2D filtered[4];  // per RGBA group: the occlusion texture with its mipmaps

// Level l's size from level 0's (textureSize with a level > 0 is not trusted here).
ivec2 mipSize(int g, int level) { return max(textureSize(filtered[g], 0) >> level, ivec2(1)); }

vec4 mipTexel(int g, ivec2 p, int level) {
    ivec2 size = mipSize(g, level);
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) return vec4(0.0);
    return texelFetch(filtered[g], p, level);
}

vec4 mipBilinear(int g, vec2 uv, int level) {
    vec2 f = uv * vec2(mipSize(g, level)) - 0.5;
    ivec2 i = ivec2(floor(f));
    vec2 w = f - vec2(i);
    return mix(mix(mipTexel(g, i, level), mipTexel(g, i + ivec2(1, 0), level), w.x),
               mix(mipTexel(g, i + ivec2(0, 1), level), mipTexel(g, i + ivec2(1, 1), level), w.x), w.y);
}

vec4 mipTrilinear(int g, vec2 uv, float lod) {
    int top = textureQueryLevels(filtered[g]) - 1;
    lod = clamp(lod, 0.0, float(top));
    int l = int(floor(lod));
    vec4 a = mipBilinear(g, uv, l);
    return l >= top ? a : mix(a, mipBilinear(g, uv, l + 1), lod - float(l));
}

vec4 boxFilter(int g, vec2 centre, vec2 size) {
    vec2 texSize = vec2(textureSize(filtered[g], 0));
    float s = max(min(size.x, size.y), 1e-6), L = max(size.x, size.y);
    int probes = clamp(int(ceil(L / s - 1e-3)), 1, 16);
    float lod = max(log2(max(s, L / 16.0)), 0.0);
    vec2 axis = size.x >= size.y ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    vec4 sum = vec4(0.0);
    for (int k = 0; k < probes; ++k) {
        float offset = (float(k) + 0.5) * L / float(probes) - 0.5 * L;
        sum += mipTrilinear(g, (centre + offset * axis) / texSize, lod);
    }
    return sum / float(probes);
}
// One channel, as the combination reads it (the SAT variant gathers that channel only).
float boxFilterChannel0(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).x; }
float boxFilterChannel1(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).y; }
float boxFilterChannel2(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).z; }
float boxFilterChannel3(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).w; }
#endif
