// How pcss shades a camera pixel: blocker search, penumbra width from the blockers' mean
// distance, then percentage-closer filtering over a kernel of that size (Fernando 2005).
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

    float sum = 0.0;
    int found = 0;
    DiskWalk search = diskWalk(uBlockerSamples, phi);
    for (int i = 0; i < uBlockerSamples; ++i) {
        vec2 q = uv + searchUv * nextDiskSample(search, i);
        ivec2 t = shadowTexel(q);
        float z = texelFetch(uShadowDistance, t, 0).r;
        if (inFrontOfReceiver(rp, t, z, dP)) {
            sum += z;
            ++found;
        }
    }
    if (found == 0) return;  // lit
    float dB = sum / float(found);
    oResult.z = dB;

    float filterUv = penumbraRadius(dP, dB) / mapWidthAt(dP);
    filterUv = max(filterUv, 0.5 / uShadowSize);  // never below half a texel: the hard shadow
    oResult.w = filterUv * uShadowSize;
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
    vec3 nABC = vec3(dot(s.normal, A), dot(s.normal, B), dot(s.normal, C));
    float aa = dot(A, A), bb = uLightSize * uLightSize;
    vec2 ab2 = 2.0 * vec2(dot(A, B), dot(A, C));
    float lit = 0.0, total = 0.0;
    DiskWalk kernel = diskWalk(uPcfSamples, phi);
    for (int i = 0; i < uPcfSamples; ++i) {
        vec2 d = nextDiskSample(kernel, i);
        float w = 1.0;
        if (uShadowOrthographic == 0) {
            float r2 = max(aa + dot(d, ab2) + bb * dot(d, d), 1e-12);
            float inv = inversesqrt(r2);
            w = max(nABC.x + dot(d, nABC.yz), 0.0) * inv * inv * inv;
        }
        total += w;
        if (w > 0.0 && !blockedAtTexel(rp, shadowTexel(uv + filterUv * d), dP)) lit += w;
    }
    oResult.x = total > 0.0 ? lit / total : 1.0;
}
