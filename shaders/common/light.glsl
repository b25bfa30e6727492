// What a light is in a shader: the uLight uniforms SceneCache::setLightUniforms() sets (core/light.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef SS_COMMON_LIGHT_GLSL
#define SS_COMMON_LIGHT_GLSL

// Same order as ss::LightType.
const int LIGHT_DISK = 0;
const int LIGHT_ELLIPSE = 1;
const int LIGHT_SQUARE = 2;
const int LIGHT_RECTANGLE = 3;
const int LIGHT_POINT = 4;
const int LIGHT_SPOT = 5;
const int LIGHT_SUN = 6;

struct LightParams {
    int type;
    vec3 position;          // centre (sun: unused)
    vec3 direction;         // unit: area normal on the emitting side, spot axis, sun travel
    vec3 halfAxisX;         // area: world half extents along the light's X and Y
    vec3 halfAxisY;
    float radius;           // point/spot sphere radius
    float equivalentRadius; // Light::equivalentRadius(): area-equal disk, sphere radius, 0 sun
    float cosHalfSpot;      // spot: cos(spot_size / 2)
    float sinHalfSun;       // sun: sin(angle / 2)
};

uniform LightParams uLight;

bool lightIsArea() { return uLight.type <= LIGHT_RECTANGLE; }

#endif
