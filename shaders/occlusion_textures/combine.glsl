// How the slices' shadows combine at a point.
// SPDX-License-Identifier: GPL-3.0-or-later
// Visibility = product over slices of (1 - w_k I_k) (paper eq. 5), I_k the box-filtered occlusion
// of slice k under the light's footprint. Needs lookup_common.glsl and one filter_*.glsl
// included before it. Points already in full umbra (V < 1e-4) skip later slices (their debug
// value is 0).

// SS_OT_SLICES, the slice count, is a define of the program variant (shading.cpp): llvmpipe runs
// both sides of an `if` under a lane mask, so a slice behind an `if` costs its lookups whether
// or not any pixel needs it. Only a loop stops early, once every lane has left it.

uniform bool skipEmptySlices;  // false only to check that skipping changes nothing (tests)

// The classifying pass's test (shading.cpp): false only where no slice can shadow the point. One
// box that holds every non-empty slice's kernel box (centres between the extreme slices' and the
// largest half size) against the union of their bounds, so one test stands for sixteen.
uniform vec4 reachRect;   // union of the non-empty slices' bounds, texels (min xy, max xy)
uniform vec4 reachScale;  // the smallest and largest centre scales (sliceScales.xy): min xy, max xy
uniform vec4 reachDepth;  // (depth a weight starts above, smallest bottom, largest bottom, unused)
uniform vec2 reachHalf;   // the largest half-size scale (sliceScales.zw / 2)
// How far the filter reads past its box: half size x factor + texels, the larger half size on
// both axes when isotropic (1) (a mipmap level or N-Buffer square spans the box's short side
// whatever the long one).
uniform vec3 reachSpread; // (factor, texels, isotropic)

bool maySliceShadow(vec3 world) {
    SlicePoint p = slicePoint((worldToLight * vec4(world, 1.0)).xyz);
    vec2 a = p.xyOverZ * reachScale.xy, b = p.xyOverZ * reachScale.zw;
    vec2 centreLo = min(a, b) + 0.5 * sliceSize, centreHi = max(a, b) + 0.5 * sliceSize;
    vec2 half_ = max(abs(p.z - reachDepth.y), abs(p.z - reachDepth.z)) * p.invZ * reachHalf;
    half_ = mix(half_, vec2(max(half_.x, half_.y)), reachSpread.z) * reachSpread.x + reachSpread.y;
    return p.z > reachDepth.x && all(bvec4(lessThan(centreLo - half_, reachRect.zw), greaterThan(centreHi + half_, reachRect.xy)));
}

#if defined(FILTER_SAT)
// The SAT picks a slice by index, so the lookups sit in one loop over the slices that can shadow
// the point: weight > 0 and the kernel reaching the slice's occupied texels (ALU only, exact:
// any other slice's box filters to 0). Most pixels need few; the loop runs as many times as the
// busiest pixel of its SIMD block needs (and at least once).

// Bit k: slice k can shadow the point.
uint slicesToRead(SlicePoint p, TangentPlane plane) {
    uint pending = 0u;
    for (int k = 0; k < SS_OT_SLICES; ++k) {
        SliceLookup s = clippedLookup(p, k, plane);
        // Bitwise, not && and ||: those become branches, and branches cost both sides here. The
        // 1e-4 is also in shading.cpp (setReachUniforms).
        uint use = uint(s.weight > 1e-4) & (uint(boxMeetsSlice(k, s.centre, s.size)) | uint(!skipEmptySlices));
        pending |= use << uint(k);
    }
    return pending;
}

// occlusion[g][c] receives w_k I_k of slice k = 4 g + c (the debug layers).
float sliceVisibility(vec3 world, vec3 normal, out vec4 occlusion[4]) {
    for (int g = 0; g < 4; ++g) occlusion[g] = vec4(0.0);
    vec3 local = (worldToLight * vec4(world, 1.0)).xyz;
    SlicePoint p = slicePoint(local);
    TangentPlane plane = tangentPlane(local, mat3(worldToLight) * normal);
    uint pending = slicesToRead(p, plane);
    float visibility = 1.0;
    while (pending != 0u && visibility >= 1e-4) {
        int k = findLSB(pending);
        pending &= pending - 1u;
        SliceLookup s = clippedLookup(p, k, plane);
        float I = clamp(boxFilterSlice(k, s.centre, s.size), 0.0, 1.0) * s.weight;
#if defined(SS_OT_SLICE_LAYERS)
        occlusion[k >> 2][k & 3] = I;  // a dynamic index costs even when nobody reads the layers
#endif
        visibility *= 1.0 - I;
    }
    return visibility;
}
#else
// Mipmaps and N-Buffers keep four slices per RGBA texture: group and channel are literals in
// each copy so every sampler-array access is constant (llvmpipe turns a dynamically indexed
// sampler array into a switch around every fetch); with the count a constant the compiler
// drops the absent slices.
#define SS_OT_SLICE(G, C)                                                                   \
    if (4 * G + C < SS_OT_SLICES && visibility >= 1e-4) {                                   \
        SliceLookup s = clippedLookup(p, 4 * G + C, plane);                                 \
        if (s.weight > 1e-4) {                                                              \
            float I = clamp(boxFilterChannel##C(G, s.centre, s.size), 0.0, 1.0) * s.weight; \
            occlusion[G][C] = I;                                                            \
            visibility *= 1.0 - I;                                                          \
        }                                                                                   \
    }
#define SS_OT_GROUP(G) SS_OT_SLICE(G, 0) SS_OT_SLICE(G, 1) SS_OT_SLICE(G, 2) SS_OT_SLICE(G, 3)

// occlusion[g][c] receives w_k I_k of slice k = 4 g + c (the debug layers).
float sliceVisibility(vec3 world, vec3 normal, out vec4 occlusion[4]) {
    for (int g = 0; g < 4; ++g) occlusion[g] = vec4(0.0);
    vec3 local = (worldToLight * vec4(world, 1.0)).xyz;
    SlicePoint p = slicePoint(local);
    TangentPlane plane = tangentPlane(local, mat3(worldToLight) * normal);
    float visibility = 1.0;
    SS_OT_GROUP(0)
    SS_OT_GROUP(1)
    SS_OT_GROUP(2)
    SS_OT_GROUP(3)
    return visibility;
}
#endif
