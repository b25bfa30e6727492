// How the dbuffer visibility of a camera pixel follows from the D-buffer (eq. 3 and eq. 4).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/camera_gbuffer.glsl"
#include "common/shadow_map.glsl"
#include "common/unseen_centre.glsl"
#include "common/visibility_contract.glsl"

uniform sampler2D uDBuffer;  // R |cx_uv|, G |cx_s| (umbra), B |cx_pv|, A |cx_s| (penumbra); 0 = none
uniform vec3 uCentre;        // disk centre c
uniform int uSmallOccluders; // V = sqrt(t) instead of 3t^2 - 2t^3
uniform int uSegmentProfile; // V = the disk's circular-segment area for a chord at t (exact in 1D)
uniform float uBiasTexels;   // receiver bias in shadow-map texels
uniform int uPaperFormula;   // eq. 3 as printed (branch condition and denominator)

layout(location = 0) out vec4 oResult;     // V, mask, umbra, penumbra
layout(location = 1) out vec4 oDistances;  // |cx_o|, |cx_uv|, |cx_pv|, |cx_s| (the one used)
// Before any clamping, so a NaN or infinity from eq. 2 or eq. 3 reaches the tests (read back
// only with debug.raw_layers=true): t of eq. 3, V of eq. 4, and the |cx_s| and volume distance used.
layout(location = 2) out vec4 oRaw;

// t of eq. 3 for a point at distance d whose ray leaves the occluder's shadow through a volume
// surface at distance b, with silhouette distance a: the share of the light's 2D section that
// lies beyond the line through x and the silhouette edge. Exact in that section; the printed
// eq. 3 has (b - a) where this has (d - a), its first-order form at the volume surface.
float sectionShare(float d, float b, float a) {
    float den = 2.0 * b * (d - a);
    return den > 0.0 || isnan(den) ? a * (d - b) / den : 0.5;  // a NaN passes on to oRaw
}

// Eq. 3's fraction exactly as printed: |cx_s| (|cx| - |cx_v|) / (2 |cx_v| (|cx_v| - |cx_s|)).
float printedShare(float d, float b, float a) { return a * (d - b) / (2.0 * b * (b - a)); }

// clamp() of a NaN is undefined in GLSL; comparisons with NaN are false, so this keeps it.
float clampKeepNaN(float x, float lo, float hi) { return x < lo ? lo : (x > hi ? hi : x); }

// The distance layers users get stay finite (0 = "no such surface"); oRaw keeps the truth.
vec4 finiteOrZero(vec4 v) {
    bvec4 bad = bvec4(isnan(v.x) || isinf(v.x), isnan(v.y) || isinf(v.y), isnan(v.z) || isinf(v.z),
                      isnan(v.w) || isinf(v.w));
    return vec4(bad.x ? 0.0 : v.x, bad.y ? 0.0 : v.y, bad.z ? 0.0 : v.z, bad.w ? 0.0 : v.w);
}

void main() {
    Surface s = loadSurface(ivec2(gl_FragCoord.xy));
    oResult = vec4(1.0, 0.0, 0.0, 0.0);
    oDistances = vec4(0.0);
    oRaw = vec4(1.0, 1.0, 0.0, 0.0);
    if (!s.receives || !lightReaches(s.position, s.normal)) return;
    oResult.y = 1.0;
    vec2 uv;
    vec3 toC = normalize(uCentre - s.position);
    // Seen from behind P's plane, the map and the D-buffer hold P's own mesh: the march towards
    // the light P sees decides, lit or umbra.
    float visible;
    if (belowHorizonDecides(s.position, s.normal, toC, visible)) {
        oResult.x = visible;
        oResult.z = 1.0 - visible;  // umbra
        return;
    }
    vec3 lookup = shadowLookupPoint(s.position, s.normal, toC);
    if (!shadowMapUv(lookup, uv)) return;
    ivec2 texel = clamp(ivec2(uv * uShadowSize), ivec2(0), ivec2(int(uShadowSize) - 1));
    float o = texelFetch(uShadowDistance, texel, 0).r;
    vec4 db = texelFetch(uDBuffer, texel, 0);
    float d = length(s.position - uCentre);
    float ds = shadowDistanceOf(lookup);
    // Slope-scaled bias: a texel covers more depth on surfaces seen at a grazing angle.
    float cosA = clamp(abs(dot(s.normal, toC)), 0.05, 1.0);
    float tanA = sqrt(1.0 - cosA * cosA) / cosA;
    float bias = shadowTexelWorldSize(ds) * uBiasTexels * (1.0 + min(tanA, 10.0));
    bool hard = o < 1e29 && o < ds - bias;
    float t, rawT;
    float b, a;
    if (uPaperFormula != 0) {
        // As printed: |cx| < |cx_o| (in front of the occluder: not in the centre's hard shadow,
        // with the receiver bias) takes the umbra volume's form, the rest 1 - (...) with the
        // penumbra volume's. With no surface of that volume along the ray the point is lit
        // (first branch) or in the umbra (second).
        if (!hard) {
            b = db.x, a = db.y;
            rawT = b > 0.0 ? printedShare(d, b, a) : 1.0;
        } else {
            b = db.z, a = db.w;
            rawT = b > 0.0 ? 1.0 - printedShare(d, b, a) : 0.0;
        }
        oDistances = vec4(o < 1e29 ? o : 0.0, db.x, db.z, a);
        oResult.z = hard && (db.x <= 0.0 || d < db.x) ? 1.0 : 0.0;
        oResult.w = !hard && db.z > 0.0 && d > db.z + bias ? 1.0 : 0.0;
        t = clampKeepNaN(rawT, 0.0, 1.0);
    } else if (hard) {
        // Shadowed from the centre: in the umbra until the ray leaves the umbra volume.
        b = db.x, a = db.y;
        oDistances = vec4(o, b, db.z, a);
        if (b <= 0.0 || d < b) {
            rawT = 0.0;
            oResult.z = 1.0;
        } else {
            rawT = sectionShare(d, b, a);
            oResult.w = 1.0;
        }
        t = clampKeepNaN(rawT, 0.0, 0.5);
    } else {
        // Lit from the centre: lit until the ray enters the penumbra volume (the symmetric
        // branch of eq. 3).
        b = db.z, a = db.w;
        oDistances = vec4(o < 1e29 ? o : 0.0, db.x, b, a);
        // The penumbra quads start on the occluder's own surface at its penumbra silhouette, so
        // on the lit occluder next to that silhouette a texel's quad fragment lies within a
        // texel (slope-scaled) in front of the receiver: the same receiver bias as the hard
        // test keeps the occluder lit there (it was speckled with V ~ 0.5).
        if (b <= 0.0 || d <= b + bias) {
            rawT = 1.0;
        } else {
            rawT = 1.0 - sectionShare(d, b, a);
            oResult.w = 1.0;
        }
        t = clampKeepNaN(rawT, 0.5, 1.0);
    }
    float V = t * t * (3.0 - 2.0 * t);
    if (uSmallOccluders != 0) {
        V = sqrt(t);
    } else if (uSegmentProfile != 0) {
        // Share of a disk beyond a chord at distance (1 - 2t) r from its centre.
        float theta = 2.0 * acos(clampKeepNaN(1.0 - 2.0 * t, -1.0, 1.0));
        V = (theta - sin(theta)) / (2.0 * 3.14159265358979);
    }
    oRaw = vec4(rawT, V, a, b);
    oDistances = finiteOrZero(oDistances);
    // The contract's V is finite and in [0, 1]; oRaw above is where a non-finite value shows.
    oResult.x = isnan(V) ? 1.0 : clamp(V, 0.0, 1.0);
}
