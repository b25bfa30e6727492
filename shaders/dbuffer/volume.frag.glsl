// What the D-buffer stores for a volume surface: its distance |cx_v| to the light centre and the
// silhouette distance |cx_s| of eq. 2, both along the ray from the centre through the fragment.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/shadow_map.glsl"

in vec3 vWorld;
flat in vec3 vEdgeA;
flat in vec3 vEdgeB;
flat in vec3 vExtrusion;
flat in int vKind;

uniform vec3 uCentre;     // disk centre c
uniform vec3 uNormal;     // disk normal, pointing into the scene
uniform float uRadius;    // disk radius r
uniform float uFar;       // distances are divided by it for the depth test
// Umbra pass with the "first exit" rule: only surfaces beyond the first caster along the ray
// (the shared shadow map, same view and size) count, and the nearest of them wins.
// uExitEpsilon (relative) keeps the caster's own surface out (a silhouette face that is the
// nearest caster is drawn at the same texels and distance up to rounding) and nothing else: the
// exit of a ray that grazes the occluder lies just behind it (see methods/dbuffer/method.cpp).
// Penumbra pass: only surfaces in front of the first caster count (uBeyondOccluder = -1). A lit
// receiver is the first caster on its own ray, so the farthest of them is the last penumbra
// volume the ray entered before reaching it; one behind it (another part's volume reaching past
// the receiver) says nothing about the receiver and made it read lit.
uniform int uBeyondOccluder;
uniform float uExitEpsilon;
// The texels (x0, y0, x1, y1) where this part's surfaces count, when x1 > x0: a part drawn in a
// layer with others is kept to its own footprint (methods/dbuffer/method.cpp, partLayers).
uniform vec4 uPartRect;
// Eq. 2 as printed, |cx_s| = (dir(c, x)·n / dir(c, e)·n) dist(c, e), and silhouette faces
// storing their own distance (formula=paper).
uniform int uPaperFormula;

const int KIND_QUAD = 0;
const int KIND_FAN = 1;
const int KIND_SILHOUETTE_FACE = 2;

// Eq. 2 for the silhouette point e: the distance of the ray's point at e's depth below the
// light plane (this code's form: the printed ratio of cosines the other way up), or the printed
// form (formula=paper), which has no guard: e in the light plane gives an infinity.
float silhouetteDistance(vec3 e, float cosRay, float dist) {
    vec3 toE = e - uCentre;
    float depthE = dot(toE, uNormal);
    if (uPaperFormula != 0) return cosRay * length(toE) * length(toE) / depthE;
    return cosRay > 1e-6 ? depthE / cosRay : dist;
}

// clamp() of a NaN is undefined in GLSL; comparisons with NaN are false, so this keeps it for
// the camera pass's raw read-back.
float clampKeepNaN(float x, float lo, float hi) { return x < lo ? lo : (x > hi ? hi : x); }

// Written to all four channels; the colour mask picks (R, G) for the umbra volume and (B, A)
// for the penumbra volume.
layout(location = 0) out vec4 oDistances;

void main() {
    vec3 toX = vWorld - uCentre;
    float dist = length(toX);
    vec3 u = toX / max(dist, 1e-30);
    float cosRay = dot(u, uNormal);
    gl_FragDepth = clamp(dist / uFar, 0.0, 1.0);
    if (uPartRect.z > uPartRect.x && (gl_FragCoord.x < uPartRect.x || gl_FragCoord.y < uPartRect.y ||
                                      gl_FragCoord.x > uPartRect.z || gl_FragCoord.y > uPartRect.w))
        discard;
    if (uBeyondOccluder != 0) {
        float o = texelFetch(uShadowDistance, ivec2(gl_FragCoord.xy), 0).r;
        float here = shadowDistanceOf(vWorld);
        if (uBeyondOccluder > 0 && !(here > o * (1.0 + uExitEpsilon))) discard;
        if (uBeyondOccluder < 0 && here > o * (1.0 + uExitEpsilon)) discard;
    }

    if (vKind == KIND_SILHOUETTE_FACE && uPaperFormula != 0) {
        // The face as a surface of the umbra volume (§3.3), its "edge" e the point of its line
        // nearest to the fragment.
        vec3 along = normalize(vEdgeB - vEdgeA);
        vec3 e = vEdgeA + along * dot(vWorld - vEdgeA, along);
        float xs = silhouetteDistance(e, cosRay, dist);
        oDistances = vec4(dist, xs, dist, xs);
        return;
    }
    if (vKind == KIND_SILHOUETTE_FACE) {
        // The face's own "edge" is the line through vEdgeA along (vEdgeB - vEdgeA), parallel to
        // the light plane. x_s: the ray at that line's depth; w: its signed offset from the line
        // across the line, positive on the face's outer side. The ray crosses the umbra plane of
        // that line (through it and the far rim point) at b = a r / (r + w): what a quad of that
        // edge would have stored, so the camera pass applies eq. 3 unchanged.
        float depthE = dot(vEdgeA - uCentre, uNormal);
        float a = cosRay > 1e-6 ? depthE / cosRay : dist;
        vec3 along = normalize(vEdgeB - vEdgeA);
        vec3 across = normalize(cross(along, uNormal));
        if (dot(across, vExtrusion) < 0.0) across = -across;
        float w = dot(uCentre + u * a - vEdgeA, across);
        float b = w + uRadius > 1e-6 * uRadius ? a * uRadius / (w + uRadius) : 1e30;
        oDistances = vec4(b, a, b, a);
        return;
    }
    // e*: the point of the silhouette edge this fragment was extruded from, where the line from
    // the extrusion point through the fragment meets the edge (exact per fragment, where the
    // paper interpolates per vertex). Fans carry a single point.
    vec3 eStar = vEdgeA;
    vec3 d1 = vEdgeB - vEdgeA;
    vec3 d2 = vWorld - vExtrusion;
    vec3 c12 = cross(d1, d2);
    float den = dot(c12, c12);
    if (vKind == KIND_QUAD && den > 1e-20 * dot(d1, d1) * dot(d2, d2)) {
        float s = dot(cross(vExtrusion - vEdgeA, d2), c12) / den;
        eStar = vEdgeA + clamp(s, 0.0, 1.0) * d1;
    }
    // Eq. 2: x_s is the point of the ray at e*'s depth below the light plane (the 2D section of
    // assumption 1); its distance from c is depth(e*) / cos(angle between ray and normal).
    float xs = silhouetteDistance(eStar, cosRay, dist);
    if (uPaperFormula == 0) xs = clampKeepNaN(xs, 0.0, dist);
    oDistances = vec4(dist, xs, dist, xs);
}
