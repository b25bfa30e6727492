// Where a shaded point reads slice k: texture centre and kernel size in texels.
// SPDX-License-Identifier: GPL-3.0-or-later
// And the slice's weight (mirrors methods/occlusion_textures_slicing.cpp, lookupSlice()).
uniform mat4 worldToLight;  // light-local: x, y in the light plane (kernel light axes), z depth
uniform vec2 lightHalf;     // half sizes of the kernel rectangle
uniform float copDistance;  // d: the slicing camera's centre of projection sits d behind the light
uniform float planes[17];   // SS_OT_SLICES + 1 depths, increasing (combine.glsl)
uniform vec2 sliceSize;     // occlusion texture size in texels
uniform int fadeRule;       // 0: fade in across the next slice (default), 1: the paper's rule

struct SliceLookup {
    vec2 centre;  // texels
    vec2 size;    // texels, full kernel width and height
    float weight;
};

SliceLookup lookupSlice(vec3 local, int k) {
    SliceLookup s;
    float top = planes[k], bottom = planes[k + 1], thickness = bottom - top;
    float z = local.z;
    s.weight = fadeRule == 1 ? clamp((z - top) / thickness, 0.0, 1.0)
                             : clamp((z - bottom) / thickness, 0.0, 1.0);
    if (z <= 0.0) s.weight = 0.0;
    // The light seen from the point covers a rectangle of the slice's lower plane centred on
    // the line from the light centre through the point: project that centre with the COP.
    float ratio = bottom / max(z, 1e-20);
    vec2 ndc = local.xy * ratio / lightHalf * (copDistance / (copDistance + bottom));
    s.centre = (0.5 * ndc + 0.5) * sliceSize;
    float halfNdc = abs(z - bottom) / max(z, 1e-20) * copDistance / (bottom + copDistance);
    s.size = halfNdc * sliceSize;
    return s;
}
