// How the slices' occupied bounds are found for the filters whose pass does not scan them (the
// SAT row pass does): one invocation per texel row of one RGBA group.
// SPDX-License-Identifier: GPL-3.0-or-later
#version 450 core
#include "occlusion_textures/slice_bounds.glsl"
layout(local_size_x = 64) in;

uniform sampler2D slices;  // one RGBA group of occlusion textures, W x H

void main() {
    ivec2 size = textureSize(slices, 0);
    int y = int(gl_GlobalInvocationID.x);
    if (y >= size.y) return;
    RowSpan row = emptyRowSpan(size.x);
    for (int x = 0; x < size.x; ++x) addTexel(row, x, texelFetch(slices, ivec2(x, y), 0));
    recordRow(row, y);
}
