// How the tests read the GL pre-filter at chosen boxes: fragment i evaluates query i.
// SPDX-License-Identifier: GPL-3.0-or-later
#version 450 core
// One of FILTER_SAT, FILTER_NBUFFER, FILTER_MIPMAP is defined by the program's variant.
#include "occlusion_textures/filter_sat.glsl"
#include "occlusion_textures/filter_nbuffer.glsl"
#include "occlusion_textures/filter_mipmap.glsl"

#if !defined(FILTER_MIPMAP)
// All four channels from the per-channel lookups the shading pass uses (the mipmap filter reads
// all four at once and defines boxFilter itself).
vec4 boxFilter(int g, vec2 centre, vec2 size) {
    return vec4(boxFilterChannel0(g, centre, size), boxFilterChannel1(g, centre, size),
                boxFilterChannel2(g, centre, size), boxFilterChannel3(g, centre, size));
}
#endif

uniform sampler2D queries;  // texel (i, 0) = (centre.x, centre.y, width, height) in texels
uniform int group;
layout(location = 0) out vec4 response;

void main() {
    vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
    response = boxFilter(group, q.xy, q.zw);
}
