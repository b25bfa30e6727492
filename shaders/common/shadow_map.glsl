// How a shader looks up the shared light-centre shadow map (SceneCache::bindShadowMap sets these).
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_COMMON_SHADOW_MAP_GLSL
#define SS_COMMON_SHADOW_MAP_GLSL

uniform sampler2D uShadowDistance;  // R32F distance to the nearest caster (1e30 = none)
uniform mat4 uShadowWorldToClip;
uniform vec3 uShadowOrigin;
uniform vec3 uShadowAxis;
uniform int uShadowOrthographic;
uniform float uShadowSize;          // texels per side
uniform float uShadowTexelScale;    // texel world size = scale * distance (perspective) or scale

// What the map stores for a world point (see ShadowMap::distanceOf).
float shadowDistanceOf(vec3 P) {
    return uShadowOrthographic != 0 ? dot(P - uShadowOrigin, uShadowAxis) : length(P - uShadowOrigin);
}

float shadowTexelWorldSize(float distanceToLight) {
    return uShadowOrthographic != 0 ? uShadowTexelScale : uShadowTexelScale * distanceToLight;
}

// Texture coordinates of P in the map; false when P falls outside it (or behind the light).
bool shadowMapUv(vec3 P, out vec2 uv) {
    vec4 clip = uShadowWorldToClip * vec4(P, 1.0);
    uv = vec2(0.0);
    if (clip.w <= 0.0) return false;
    vec3 ndc = clip.xyz / clip.w;
    uv = ndc.xy * 0.5 + 0.5;
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

// Normal offset (Holbert, "Saying goodbye to shadow acne", 2011): the point a receiver looks up
// moves off its surface along the normal by kNormalOffsetTexels texel footprints x sin(theta).
// Slope bias alone leaves acne at the terminator of faceted curved surfaces, where the texel
// holds a neighbouring facet far steeper than the receiver's own.
const float kNormalOffsetTexels = 3.0;

vec3 shadowLookupPoint(vec3 P, vec3 N, vec3 toLight) {
    float cosT = clamp(abs(dot(N, toLight)), 0.0, 1.0);
    float sinT = sqrt(1.0 - cosT * cosT);
    return P + N * (shadowTexelWorldSize(shadowDistanceOf(P)) * kNormalOffsetTexels * sinT);
}

// Whether the map's ray from the light centre reaches P from in front of P's tangent plane
// (toLight: unit direction from P to the centre, or to a sun). Where it does not, the centre is
// on or below P's horizon while some of the light may be above it (lightReaches): every surface
// the map holds along that ray lies behind the plane, where nothing can block light that reaches
// P, so P's own texel holds no evidence of a shadow (the hard-shadow methods march towards the
// light P sees instead: common/unseen_centre.glsl). Read there, the faces of a lit caster that
// see the light but not its centre (a box's sides under a light wider than its top, the band of
// a sphere between the centre's terminator and the light's) found their own mesh and came out
// black (tests/native/test_lit_caster_faces.cpp).
bool centreAboveHorizon(vec3 N, vec3 toLight) { return dot(N, toLight) > 0.0; }

#endif
