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
uniform vec2 lightHalfSize;  // the kernel light's half sizes along its local x and y

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

// The part of the light whose rays to P cross slice k in front of P's tangent plane, as the
// largest axis-aligned box inside it, in units of the light's half sizes: (centre, half size);
// the whole light (0, 0, 1, 1) when all of it qualifies, nothing (0) when none does. A ray from
// a light point below P's horizon reaches P through its own surface's unlit side, so what a
// slice holds there is P's own mesh seen from behind, never a blocker (without the clip a lit
// caster's faces that see part of the light shadowed themselves;
// tests/native/test_lit_caster_faces.cpp). A slice is flattened
// onto its lower plane through the slicing camera, so the mesh behind P's plane spreads there up
// to the farther of two parallel lines: the plane's trace on the lower plane and its trace on the
// upper plane as the camera projects it (lower = m upper + (0, 0, oz), sliceProjections[k]).
// With light points L = (a hx, b hy, 0), (a, b) in [-1, 1]^2, a line is alpha a + beta b = gamma
// and the points in front satisfy alpha a + beta b > gamma. Mirrored so that (1, 1) is the most
// visible corner, the box [1 - u, 1] x [1 - v, 1] with its far corner on the line,
// A u + B v = R, is largest at u = R / 2A, v = R / 2B, each at most 2 (the square's side).
uniform vec2 sliceProjections[16];  // (m, oz): where the slicing camera puts upper-plane points

struct TangentPlane {
    vec3 normal;  // light-local
    float alpha, beta, np;  // normal.x hx, normal.y hy, dot(normal, P)
};

TangentPlane tangentPlane(vec3 local, vec3 normal) {
    TangentPlane t;
    t.normal = normal;
    t.alpha = normal.x * lightHalfSize.x;
    t.beta = normal.y * lightHalfSize.y;
    t.np = dot(normal, local);
    return t;
}

// margin: one texel in the box's units; a clipped side moves in by it, off the texels the mesh
// behind the plane only partly covers.
vec4 boxAbove(float alpha, float beta, float gamma, vec2 margin) {
    float A = abs(alpha), B = abs(beta), R = A + B - gamma;
    if (R >= 2.0 * (A + B)) return vec4(0.0, 0.0, 1.0, 1.0);
    if (R <= 0.0) return vec4(0.0);
    float u = A > 0.0 ? R / (2.0 * A) : 2.0, v = B > 0.0 ? R / (2.0 * B) : 2.0;
    if (u > 2.0) u = 2.0, v = min((R - 2.0 * A) / B, 2.0);
    else if (v > 2.0) v = 2.0, u = min((R - 2.0 * B) / A, 2.0);
    if (u < 2.0) u -= margin.x;
    if (v < 2.0) v -= margin.y;
    if (u <= 0.0 || v <= 0.0) return vec4(0.0);
    vec2 dir = vec2(alpha < 0.0 ? -1.0 : 1.0, beta < 0.0 ? -1.0 : 1.0);
    return vec4(dir * (1.0 - 0.5 * vec2(u, v)), 0.5 * vec2(u, v));
}

// Slice k's lookup restricted to that box (the kernel is the light scaled through P). A lower
// plane point X = f L + g P (f = (z - b) / z, g = b / z) is in front of the plane's upper trace
// where f N.L > N.o + (m - g) N.P, on its own trace where N.L > N.P. Slices P lies above only
// (f > 0); with fade=paper the slice holding P keeps its whole kernel.
SliceLookup clippedLookup(SlicePoint p, int k, TangentPlane t) {
    SliceLookup s = lookupSlice(p, k);
    float bottom = sliceDepths[k].y, f = (p.z - bottom) * p.invZ;
    if (f <= 0.0) return s;
    vec2 proj = sliceProjections[k];
    float upper = (t.normal.z * proj.y + (proj.x - bottom * p.invZ) * t.np) / f;
    vec4 box = boxAbove(t.alpha, t.beta, max(t.np, upper), 2.0 / max(s.size, vec2(1e-6)));
    s.centre += box.xy * 0.5 * s.size;
    s.size *= box.zw;
    if (box.z <= 0.0) s.weight = 0.0;
    return s;
}
