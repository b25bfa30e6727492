// How the slices' shadows combine at a point: visibility = product over slices of (1 - w_k I_k)
// (paper eq. 5), I_k the box-filtered occlusion of slice k under the light's footprint.
// Needs lookup_common.glsl and one filter_*.glsl (boxFilter) included before it.
// SPDX-License-Identifier: GPL-3.0-or-later

// occlusion[g][c] receives w_k I_k of slice k = 4 g + c (the debug layers).
float sliceVisibility(vec3 world, out vec4 occlusion[4]) {
    for (int g = 0; g < 4; ++g) occlusion[g] = vec4(0.0);
    vec3 local = (worldToLight * vec4(world, 1.0)).xyz;
    float visibility = 1.0;
    for (int k = 0; k < sliceCount; ++k) {
        SliceLookup s = lookupSlice(local, k);
        if (s.weight <= 0.0) continue;
        float I = clamp(boxFilter(k / 4, s.centre, s.size)[k % 4], 0.0, 1.0) * s.weight;
        occlusion[k / 4][k % 4] = I;
        visibility *= 1.0 - I;
    }
    return visibility;
}
