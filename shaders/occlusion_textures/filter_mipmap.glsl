// How a box is read from mipmaps: trilinear lookups at the level of the kernel's short side.
// SPDX-License-Identifier: GPL-3.0-or-later
// Spread along its long side (anisotropic filtering done here, mirrors filters/box_filter.cpp:
// llvmpipe's own GL_TEXTURE_MAX_ANISOTROPY path measured 4x further from the exact box). (A
// texelFetch trilinear, as the N-Buffers use, returned wrong levels > 0 here: not used.)
// Compiled only in the FILTER_MIPMAP variant: the three filters share one include list.
#if defined(FILTER_MIPMAP)
uniform sampler2D filtered[4];  // per RGBA group: the occlusion texture with its mipmaps

vec4 boxFilter(int g, vec2 centre, vec2 size) {
    vec2 texSize = vec2(textureSize(filtered[g], 0));
    float s = max(min(size.x, size.y), 1e-6), L = max(size.x, size.y);
    int probes = clamp(int(ceil(L / s - 1e-3)), 1, 16);
    float lod = max(log2(max(s, L / 16.0)), 0.0);
    vec2 axis = size.x >= size.y ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    vec4 sum = vec4(0.0);
    for (int k = 0; k < probes; ++k) {
        float offset = (float(k) + 0.5) * L / float(probes) - 0.5 * L;
        sum += textureLod(filtered[g], (centre + offset * axis) / texSize, lod);
    }
    return sum / float(probes);
}
// One channel, as the combination reads it (the SAT variant gathers that channel only).
float boxFilterChannel0(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).x; }
float boxFilterChannel1(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).y; }
float boxFilterChannel2(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).z; }
float boxFilterChannel3(int g, vec2 centre, vec2 size) { return boxFilter(g, centre, size).w; }
#endif
