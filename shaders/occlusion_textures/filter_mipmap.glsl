// How a box is read from mipmaps: a trilinear lookup whose gradients are the kernel's sides, so
// the texture unit's anisotropic filter takes rectangular kernels (GL_TEXTURE_MAX_ANISOTROPY).
// SPDX-License-Identifier: GPL-3.0-or-later
// Compiled only in the FILTER_MIPMAP variant: the three filters share one include list.
#if defined(FILTER_MIPMAP)
uniform sampler2D filtered[4];  // per RGBA group: the occlusion texture with its mipmaps

vec4 boxFilter(int g, vec2 centre, vec2 size) {
    vec2 texSize = vec2(textureSize(filtered[g], 0));
    return textureLod(filtered[g], centre / texSize, log2(max(min(size.x, size.y), 1.0)));
}
#endif
