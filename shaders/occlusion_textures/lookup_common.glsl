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

struct SliceLookup {
    vec2 centre;  // texels
    vec2 size;    // texels, full kernel width and height
    float weight;
};

SliceLookup lookupSlice(vec3 local, int k) {
    vec4 depths = sliceDepths[k], scales = sliceScales[k];
    float z = local.z, invZ = 1.0 / max(z, 1e-20);
    SliceLookup s;
    s.weight = z <= 0.0 ? 0.0 : clamp((z - (fadeRule == 1 ? depths.x : depths.y)) * depths.z, 0.0, 1.0);
    s.centre = local.xy * invZ * scales.xy + 0.5 * sliceSize;
    s.size = abs(z - depths.y) * invZ * scales.zw;
    return s;
}
