// How a full-screen pass reads the shared camera G-buffer (SceneCache::bindCameraPass sets these).
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_COMMON_CAMERA_GBUFFER_GLSL
#define SS_COMMON_CAMERA_GBUFFER_GLSL

uniform sampler2D uCamPositionDepth;  // xyz world position, w view depth (0 = no surface)
uniform sampler2D uCamNormalReceive;  // xyz unit normal facing the camera, w receive flag
uniform sampler2D uCamIds;            // x mesh index, y triangle index (-1 background)

struct Surface {
    vec3 position;
    float viewDepth;
    vec3 normal;
    bool covered;   // a surface is seen through this pixel
    bool receives;  // ... and its mesh receives shadows
};

// pixel: GL fragment coordinates (ivec2(gl_FragCoord.xy) in a camera-resolution pass).
Surface loadSurface(ivec2 pixel) {
    vec4 pd = texelFetch(uCamPositionDepth, pixel, 0);
    vec4 nr = texelFetch(uCamNormalReceive, pixel, 0);
    Surface s;
    s.position = pd.xyz;
    s.viewDepth = pd.w;
    s.normal = nr.xyz;
    s.covered = pd.w > 0.0;
    s.receives = s.covered && nr.w > 0.5;
    return s;
}

#endif
