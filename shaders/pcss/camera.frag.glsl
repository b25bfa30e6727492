// How pcss shades a camera pixel: blocker search, penumbra width from the blockers' distance,
// then percentage-closer filtering over a kernel of that size (Fernando 2005), once per layer of
// casters (far from P, and near it).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/camera_gbuffer.glsl"
#include "common/visibility_contract.glsl"
#include "pcss/receiver_plane.glsl"

uniform int uBlockerSamples;
uniform int uPcfSamples;
uniform float uLightSize;     // perspective: light radius (world); orthographic: tan(sun half angle)
uniform float uNearCaster;    // map quantity (distance) of the nearest caster the search allows for
uniform float uMaxSearchUv;   // cap on the blocker-search radius, in map widths

layout(location = 0) out vec4 oResult;  // V, mask, mean blocker distance (0 none), kernel radius (texels)

// Samples on a unit disk along a Vogel spiral (even density), turned by a per-pixel angle.
// Each sample's direction is the last one turned by the golden angle: a rotation costs four
// multiply-adds where cos and sin per sample made the loops several times slower on llvmpipe.
struct DiskWalk {
    vec2 dir;   // direction of the next sample
    int n;
};

const vec2 kGoldenTurn = vec2(-0.73736887, 0.67549029);  // cos, sin of 2.39996323 rad

DiskWalk diskWalk(int n, float phi) { return DiskWalk(vec2(cos(phi), sin(phi)), n); }

// Sample i of the walk (called for i = 0, 1, 2 ...).
vec2 nextDiskSample(inout DiskWalk w, int i) {
    vec2 d = sqrt((float(i) + 0.5) / float(w.n)) * w.dir;
    w.dir = vec2(w.dir.x * kGoldenTurn.x - w.dir.y * kGoldenTurn.y, w.dir.x * kGoldenTurn.y + w.dir.y * kGoldenTurn.x);
    return d;
}

// The map's width in world units at map quantity d.
float mapWidthAt(float d) { return shadowTexelWorldSize(d) * uShadowSize; }

// Radius of the penumbra at a receiver at dR behind blockers at dB, in world units.
float penumbraRadius(float dR, float dB) {
    if (uShadowOrthographic != 0) return (dR - dB) * uLightSize;
    return uLightSize * (dR - dB) / max(dB, 1e-6);
}

// Whether a caster at map quantity z, offUv map widths from P's own texel, can hide any of the
// light from P: the line from P through it must meet the light. Seen from P, the light covers a
// disk of radius uLightSize (dP - z) / dP world units at the caster's distance z, so the caster
// counts only within that radius of P's texel (plus one texel, for where inside its texel the
// caster lies). The blocker search, sized for the nearest caster, also finds surfaces far from
// P's line of sight that only stand in front of P's plane (a wavy receiver's own hills, the
// steps above a lower step); counted, their distance, close to P's, shrank the penumbra to a
// hard edge (tests/native/test_pcss_layers.cpp). reachScale is dP x the map's width per unit of
// distance (perspective) or its width (orthographic, where the reach is (dP - z) tan).
bool canBlock(float offUv, float z, float dP, float reachScale) {
    float off = max(offUv - 1.0 / uShadowSize, 0.0) * reachScale;
    return (uShadowOrthographic != 0 ? off : off * z) <= uLightSize * (dP - z);
}

// The PCF kernel's radius in map widths for casters at distance dB: never below half a texel
// (the hard shadow).
float kernelUv(float dP, float dB) {
    return max(penumbraRadius(dP, dB) / mapWidthAt(dP), 0.5 / uShadowSize);
}

// Per-pixel dot products for a kernel sample's irradiance weight (see main).
struct LightWeights {
    vec3 nABC;
    float aa, bb;
    vec2 ab2;
};

// Weighted share of the kernel's samples not blocked by the layer's casters (near: beyond
// `split` from the light; far: up to it, and near ones this kernel's sample can block: a thick
// caster reaches into the near layer, and its deep parts there keep its umbra dark). A texel
// whose caster is in the other layer holds none of this one's: the map keeps the caster
// nearest the light.
float filtered(ReceiverPlane rp, LightWeights lw, vec2 uv, float filterUv, float dP, float split, bool near,
               float reachScale, float phi, int samples) {
    float lit = 0.0, total = 0.0;
    DiskWalk kernel = diskWalk(samples, phi);
    for (int i = 0; i < samples; ++i) {
        vec2 d = nextDiskSample(kernel, i);
        float w = 1.0;
        if (uShadowOrthographic == 0) {
            float r2 = max(lw.aa + dot(d, lw.ab2) + lw.bb * dot(d, d), 1e-12);
            float inv = inversesqrt(r2);
            w = max(lw.nABC.x + dot(d, lw.nABC.yz), 0.0) * inv * inv * inv;
        }
        total += w;
        if (w <= 0.0) continue;
        ivec2 t = shadowTexel(uv + filterUv * d);
        float z = texelFetch(uShadowDistance, t, 0).r;
        bool layer = near ? z > split : z <= split || canBlock(filterUv * length(d), z, dP, reachScale);
        if (!layer || !inFrontOfReceiver(rp, t, z, dP)) lit += w;
    }
    return total > 0.0 ? lit / total : 1.0;
}

void main() {
    Surface s = loadSurface(ivec2(gl_FragCoord.xy));
    oResult = vec4(1.0, 0.0, 0.0, 0.0);
    if (!s.receives || !lightReaches(s.position, s.normal)) return;
    oResult.y = 1.0;
    vec2 uv;
    vec3 toLight = uShadowOrthographic != 0 ? -uShadowAxis : normalize(uShadowOrigin - s.position);
    vec3 P = shadowLookupPoint(s.position, s.normal, toLight);
    if (!shadowMapUv(P, uv)) return;  // outside the map: nothing casts onto it
    float dP = shadowDistanceOf(P);
    ReceiverPlane rp = receiverPlane(P, s.normal);
    // Interleaved gradient noise turns the pattern per pixel: banding becomes fine noise.
    float phi = 6.2831853 * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));

    // Blockers can sit anywhere between the nearest caster and the receiver; the widest
    // footprint of the light seen from P is at the nearest caster's distance.
    float nearD = min(uNearCaster, dP);
    float searchWorld = uShadowOrthographic != 0 ? (dP - nearD) * uLightSize
                                                 : uLightSize * (dP - nearD) / dP;
    float searchUv = min(searchWorld / mapWidthAt(nearD), uMaxSearchUv);
    searchUv = max(searchUv, 1.0 / uShadowSize);

    // Two layers of casters, split halfway between the nearest caster and P, each with its own
    // distance and filter; the visibilities multiply (their occlusion taken as independent).
    // With one for both, a contact (a step's edge just above a lower step) under a far caster's
    // penumbra came out nearly lit: the far caster's wide kernel sampled the contact's few texels
    // sparsely, and the contact's closeness to P narrowed the far caster's penumbra.
    // A layer's distance is that of its casters that can block (canBlock): for the far layer the
    // farthest of them, where the penumbra's edges are made (the mean was the caster's front,
    // nearer the light, and its kernel too wide: umbrae under a sphere or Suzanne came out at
    // V = 0.1-0.3, on the bench scenes' receivers RMSE 0.032 -> 0.011 on curved_receiver, 0.025
    // -> 0.020 on concave); for the near layer, the mean. Where the samples hit none that can
    // block, as along a penumbra's outer rim, where the blocker fills a sliver of the search
    // disk, the layer's casters in front of P's plane give the mean, and the filter decides.
    float split = 0.5 * (nearD + dP);
    float reachScale = uShadowOrthographic != 0 ? mapWidthAt(dP) : dP * mapWidthAt(1.0);
    float farthest = 0.0;  // of the far layer's casters that can block
    // Casters that .x: are far and can block, .y: are far, .z: are near and can block, .w: are
    // near (all in front of P's plane): how many, and their distances' sums.
    vec4 sums = vec4(0.0), counts = vec4(0.0);
    DiskWalk search = diskWalk(uBlockerSamples, phi);
    for (int i = 0; i < uBlockerSamples; ++i) {
        vec2 o = searchUv * nextDiskSample(search, i);
        ivec2 t = shadowTexel(uv + o);
        float z = texelFetch(uShadowDistance, t, 0).r;
        if (!inFrontOfReceiver(rp, t, z, dP)) continue;
        bool far = z <= split;
        bool blocks = canBlock(length(o), z, dP, reachScale);
        if (far && blocks) farthest = max(farthest, z);
        vec4 hit = vec4(far && blocks ? 1.0 : 0.0, far ? 1.0 : 0.0, !far && blocks ? 1.0 : 0.0, far ? 0.0 : 1.0);
        sums += z * hit;
        counts += hit;
    }
    // The near layer's casters can hide the light only within reach(split) of P's texel, and
    // within a texel or two where they touch P: radii from P's own texel out to that reach,
    // growing geometrically, find them at every scale (the far search's spacing, sized for the
    // nearest caster, mostly steps over them). Half the taps, and half the samples for the near
    // layer's filter: on the bench scenes' receivers within 0.0006 of the full counts.
    float nearReach = uLightSize * (dP - split) / (reachScale * (uShadowOrthographic != 0 ? 1.0 : split));
    float radius = 1.0 / uShadowSize;
    int nearTaps = max(uBlockerSamples / 2, 2);
    float grow = pow(max(nearReach * uShadowSize, 1.0), 1.0 / float(nearTaps - 1));
    DiskWalk nearSearch = diskWalk(nearTaps, phi + 1.0);
    for (int i = 0; i < nearTaps; ++i) {
        vec2 o = (i == 0 ? 0.0 : radius) * nearSearch.dir;
        nextDiskSample(nearSearch, i);  // turns the direction
        if (i > 0) radius *= grow;
        ivec2 t = shadowTexel(uv + o);
        float z = texelFetch(uShadowDistance, t, 0).r;
        if (z <= split || !inFrontOfReceiver(rp, t, z, dP)) continue;
        vec2 hit = vec2(canBlock(length(o), z, dP, reachScale) ? 1.0 : 0.0, 1.0);
        sums.zw += z * hit;
        counts.zw += hit;
    }
    if (counts.y + counts.w == 0.0) return;  // lit
    float dFar = counts.x > 0.0 ? farthest : counts.y > 0.0 ? sums.y / counts.y : 0.0;
    float dNear = counts.z > 0.0 ? sums.z / counts.z : counts.w > 0.0 ? sums.w / counts.w : 0.0;
    oResult.z = dFar > 0.0 ? dFar : dNear;

    // The contract weighs the light by the irradiance it sends. A kernel sample at offset
    // filterUv * d stands for the light point C + R d (the line from P through the sample's
    // blocker meets the light there, on the same side), so each sample is weighted by that
    // point's cos(P) / r^2 (cos(L) varies by a few percent across a light and is left out); the
    // part of the light below P's horizon weighs nothing.
    // Without it, curved occluders got V ~ 0.6 along their terminators where the truth is 1:
    // the samples "blocked" there by the occluder itself are light the point cannot see anyway.
    // With toL = A + d.x B + d.y C (B, C the light's radius along the map's right and up, which
    // are orthogonal), cos and r^2 per sample are a few multiply-adds of per-pixel dot products.
    vec3 A = uShadowOrigin - s.position;
    vec3 B = uLightSize * normalize(uShadowRayBasis[0]), C = uLightSize * normalize(uShadowRayBasis[1]);
    LightWeights lw = LightWeights(vec3(dot(s.normal, A), dot(s.normal, B), dot(s.normal, C)), dot(A, A),
                                   uLightSize * uLightSize, 2.0 * vec2(dot(A, B), dot(A, C)));
    float vFar = 1.0, vNear = 1.0;
    if (dFar > 0.0) {
        float filterUv = kernelUv(dP, dFar);
        oResult.w = filterUv * uShadowSize;
        vFar = filtered(rp, lw, uv, filterUv, dP, split, false, reachScale, phi, uPcfSamples);
    }
    if (dNear > 0.0) {
        float filterUv = kernelUv(dP, dNear);
        if (dFar == 0.0) oResult.w = filterUv * uShadowSize;
        vNear = filtered(rp, lw, uv, filterUv, dP, split, true, reachScale, phi, max(uPcfSamples / 2, 1));
    }
    oResult.x = vFar * vNear;
}
