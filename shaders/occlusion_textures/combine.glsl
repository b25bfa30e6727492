// How the slices' shadows combine at a point.
// SPDX-License-Identifier: GPL-3.0-or-later
// Visibility = product over slices of (1 - w_k I_k) (paper eq. 5), I_k the box-filtered occlusion
// of slice k under the light's footprint. Needs lookup_common.glsl and one filter_*.glsl
// (boxFilterChannel0..3) included before it.

// SS_OT_SLICES, the slice count, is a define of the program variant (shading.cpp): llvmpipe runs
// both sides of an `if` under a lane mask, so with a uniform count every one of the 16 possible
// slices cost its lookups; with a constant the compiler drops the absent ones. Group and channel
// are literals in each copy so every sampler-array access is constant (llvmpipe turns a
// dynamically indexed sampler array into a switch around every fetch) and the SAT filter can
// gather that channel alone. Points already in full umbra (V < 1e-4) skip later slices (their
// debug value is 0).
#define SS_OT_SLICE(G, C)                                                                   \
    if (4 * G + C < SS_OT_SLICES && visibility >= 1e-4) {                                   \
        SliceLookup s = lookupSlice(local, 4 * G + C);                                      \
        if (s.weight > 0.0) {                                                               \
            float I = clamp(boxFilterChannel##C(G, s.centre, s.size), 0.0, 1.0) * s.weight; \
            occlusion[G][C] = I;                                                            \
            visibility *= 1.0 - I;                                                          \
        }                                                                                   \
    }
#define SS_OT_GROUP(G) SS_OT_SLICE(G, 0) SS_OT_SLICE(G, 1) SS_OT_SLICE(G, 2) SS_OT_SLICE(G, 3)

// occlusion[g][c] receives w_k I_k of slice k = 4 g + c (the debug layers).
float sliceVisibility(vec3 world, out vec4 occlusion[4]) {
    for (int g = 0; g < 4; ++g) occlusion[g] = vec4(0.0);
    vec3 local = (worldToLight * vec4(world, 1.0)).xyz;
    float visibility = 1.0;
    SS_OT_GROUP(0)
    SS_OT_GROUP(1)
    SS_OT_GROUP(2)
    SS_OT_GROUP(3)
    return visibility;
}
