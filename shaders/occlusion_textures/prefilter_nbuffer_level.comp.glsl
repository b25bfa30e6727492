// How N-Buffer level l is made from level l-1.
// SPDX-License-Identifier: GPL-3.0-or-later
// The mean of four boxes of side 2^(l-1) whose lower corners are this texel and its neighbours
// 2^(l-1) away (outside the texture: 0). Level 0 is a copy of the occlusion textures (half = 0).
#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2DArray levels;  // the N-Buffer so far; layer = level
uniform sampler2D slices;       // the occlusion textures (level 0 source)
uniform int level;
layout(rgba16f, binding = 0) uniform writeonly image2DArray target;

vec4 fetch(ivec2 p) {
    ivec2 size = textureSize(slices, 0);
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) return vec4(0.0);
    return texelFetch(levels, ivec3(p, level - 1), 0);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(slices, 0);
    if (p.x >= size.x || p.y >= size.y) return;
    vec4 value;
    if (level == 0) {
        value = texelFetch(slices, p, 0);
    } else {
        int h = 1 << (level - 1);
        value = 0.25 * (fetch(p) + fetch(p + ivec2(h, 0)) + fetch(p + ivec2(0, h)) + fetch(p + ivec2(h, h)));
    }
    imageStore(target, ivec3(p, level), value);
}
