// What the D-buffer stores for a volume surface: its distance |cx_v| to the light centre and the
// silhouette distance |cx_s| of eq. 2, both along the ray from the centre through the fragment.
// SPDX-License-Identifier: GPL-3.0-or-later
in vec3 vWorld;
flat in vec3 vEdgeA;
flat in vec3 vEdgeB;
flat in vec3 vExtrusion;

uniform vec3 uCentre;     // disk centre c
uniform vec3 uNormal;     // disk normal, pointing into the scene
uniform float uFar;       // distances are divided by it for the depth test

// Written to all four channels; the colour mask picks (R, G) for the umbra volume and (B, A)
// for the penumbra volume.
layout(location = 0) out vec4 oDistances;

void main() {
    vec3 toX = vWorld - uCentre;
    float dist = length(toX);
    vec3 u = toX / max(dist, 1e-30);
    // e*: the point of the silhouette edge this fragment was extruded from, where the line from
    // the extrusion point through the fragment meets the edge (exact per fragment, where the
    // paper interpolates per vertex). Fans and silhouette faces carry a single point.
    vec3 eStar = vEdgeA;
    vec3 d1 = vEdgeB - vEdgeA;
    vec3 d2 = vWorld - vExtrusion;
    vec3 c12 = cross(d1, d2);
    float den = dot(c12, c12);
    if (den > 1e-20 * dot(d1, d1) * dot(d2, d2)) {
        float s = dot(cross(vExtrusion - vEdgeA, d2), c12) / den;
        eStar = vEdgeA + clamp(s, 0.0, 1.0) * d1;
    }
    // Eq. 2: x_s is the point of the ray at e*'s depth below the light plane (the 2D section of
    // assumption 1); its distance from c is depth(e*) / cos(angle between ray and normal).
    float cosRay = dot(u, uNormal);
    float depthE = dot(eStar - uCentre, uNormal);
    float xs = cosRay > 1e-6 ? depthE / cosRay : dist;
    xs = clamp(xs, 0.0, dist);
    oDistances = vec4(dist, xs, dist, xs);
    gl_FragDepth = clamp(dist / uFar, 0.0, 1.0);
}
