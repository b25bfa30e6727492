// How a shader looks up the shared light-centre shadow map (Frame::bindShadowMap sets these).
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

#endif
