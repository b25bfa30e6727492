// How occlusion_textures shades the camera G-buffer.
// SPDX-License-Identifier: GPL-3.0-or-later
// Visibility from the pre-filtered slices (product combination), the shared mask, and each slice's
// weighted shadow for the debug layers.
#version 450 core
#include "common/camera_gbuffer.glsl"
#include "common/visibility_contract.glsl"
#include "occlusion_textures/lookup_common.glsl"
// One of FILTER_SAT, FILTER_NBUFFER, FILTER_MIPMAP is defined by the program's variant.
#include "occlusion_textures/filter_sat.glsl"
#include "occlusion_textures/filter_nbuffer.glsl"
#include "occlusion_textures/filter_mipmap.glsl"
#include "occlusion_textures/combine.glsl"

// The pass runs twice (shading.cpp): SS_OT_CLASSIFY writes every pixel as lit and marks in depth
// the pixels some slice may shadow (one test, maySliceShadow); the full pass then runs behind an
// early depth test on those alone. llvmpipe skips a pixel block whose depth test fails
// everywhere, where a branch or a discard inside the shader skips nothing.
#if !defined(SS_OT_CLASSIFY)
layout(early_fragment_tests) in;
#endif

layout(location = 0) out vec2 result;  // x = V, y = mask
layout(location = 1) out vec4 slices0;  // w_k I_k of slices 0..3
layout(location = 2) out vec4 slices1;
layout(location = 3) out vec4 slices2;
layout(location = 4) out vec4 slices3;

void main() {
    Surface s = loadSurface(ivec2(gl_FragCoord.xy));
    vec4 occlusion[4] = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    bool reached = s.receives && lightReaches(s.position, s.normal);
    float visibility = 1.0;
#if defined(SS_OT_CLASSIFY)
    gl_FragDepth = reached && maySliceShadow(s.position) ? 0.0 : 1.0;
#else
    if (reached) visibility = clamp(sliceVisibility(s.position, s.normal, occlusion), 0.0, 1.0);
#endif
    result = vec2(visibility, reached ? 1.0 : 0.0);
    slices0 = occlusion[0];
    slices1 = occlusion[1];
    slices2 = occlusion[2];
    slices3 = occlusion[3];
}
