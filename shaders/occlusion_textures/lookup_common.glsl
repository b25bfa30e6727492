// Where a shaded point reads slice k: texture centre and kernel size in texels.
// SPDX-License-Identifier: GPL-3.0-or-later
// And the slice's weight (mirrors native/src/methods/occlusion_textures/slicing.cpp, lookupSlice()).
uniform mat4 worldToLight;  // light-local: x, y in the light plane (kernel light axes), z depth
uniform vec2 sliceSize;     // occlusion texture size in texels
uniform int fadeRule;       // 0: fade in across the next slice (default), 1: the paper's rule
// Per slice, from the slicing camera (shading.cpp), so a lookup is a few multiply-adds:
// sliceDepths[k] = (top plane, bottom plane, 1 / thickness, unused);
// sliceScales[k].xy: the kernel centre is local.xy / z * scale + sliceSize / 2 (the line from
// the light centre through the point meets the lower plane, projected by the COP);
// sliceScales[k].zw: the kernel size is |z - bottom| / z * scale (the light's footprint there).
uniform vec4 sliceDepths[16];
uniform vec4 sliceScales[16];

// The shaded point as every slice lookup needs it (computed once per point).
struct SlicePoint {
    vec2 xyOverZ;  // light-local x, y over depth
    float z;       // light-local depth
    float invZ;
};

SlicePoint slicePoint(vec3 local) {
    SlicePoint p;
    p.z = local.z;
    p.invZ = 1.0 / max(local.z, 1e-20);
    p.xyOverZ = local.xy * p.invZ;
    return p;
}

struct SliceLookup {
    vec2 centre;  // texels
    vec2 size;    // texels, full kernel width and height
    float weight;
};

SliceLookup lookupSlice(SlicePoint p, int k) {
    vec4 depths = sliceDepths[k], scales = sliceScales[k];
    SliceLookup s;
    s.weight = p.z <= 0.0 ? 0.0 : clamp((p.z - (fadeRule == 1 ? depths.x : depths.y)) * depths.z, 0.0, 1.0);
    s.centre = p.xyOverZ * scales.xy + 0.5 * sliceSize;
    s.size = abs(p.z - depths.y) * p.invZ * scales.zw;
    return s;
}
