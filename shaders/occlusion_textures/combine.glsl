// How the slices' shadows combine at a point.
// SPDX-License-Identifier: GPL-3.0-or-later
// Visibility = product over slices of (1 - w_k I_k) (paper eq. 5), I_k the box-filtered occlusion
// of slice k under the light's footprint. Needs lookup_common.glsl and one filter_*.glsl
// (boxFilter) included before it.

// The group index is a literal in each copy so every sampler-array access is constant:
// llvmpipe turns a dynamically indexed sampler array into a switch around every fetch.
// Once the point is in full umbra (V < 1e-4) later slices are skipped (their debug value is 0).
#define SS_OT_GROUP(G)                                                                  \
    for (int c = 0; c < 4 && visibility >= 1e-4; ++c) {                                \
        int k = 4 * G + c;                                                              \
        if (k >= sliceCount) break;                                                     \
        SliceLookup s = lookupSlice(local, k);                                          \
        if (s.weight <= 0.0) continue;                                                  \
        float I = clamp(boxFilter(G, s.centre, s.size)[c], 0.0, 1.0) * s.weight;        \
        occlusion[G][c] = I;                                                            \
        visibility *= 1.0 - I;                                                          \
    }

// occlusion[g][c] receives w_k I_k of slice k = 4 g + c (the debug layers).
float sliceVisibility(vec3 world, out vec4 occlusion[4]) {
    for (int g = 0; g < 4; ++g) occlusion[g] = vec4(0.0);
    vec3 local = (worldToLight * vec4(world, 1.0)).xyz;
    float visibility = 1.0;
    SS_OT_GROUP(0)
    if (sliceCount > 4) SS_OT_GROUP(1)
    if (sliceCount > 8) SS_OT_GROUP(2)
    if (sliceCount > 12) SS_OT_GROUP(3)
    return visibility;
}
