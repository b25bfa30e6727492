// Where a mesh's object-space vertex and face normal are in the world (setPlacementUniforms, scene_cache/shader_uniforms.h, sets them).
// SPDX-License-Identifier: GPL-3.0-or-later
uniform int uTransformed;      // 0: the coordinates are world coordinates already
uniform mat4 uObjectToWorld;
uniform mat4 uNormalToWorld;   // inverse transpose of the 3x3 part

vec3 meshToWorld(vec3 p) {
    return uTransformed != 0 ? (uObjectToWorld * vec4(p, 1.0)).xyz : p;
}

// Zero (a degenerate face) stays zero.
vec3 meshNormalToWorld(vec3 n) {
    if (uTransformed == 0) return n;
    vec3 w = mat3(uNormalToWorld) * n;
    float len = length(w);
    return len > 0.0 ? w / len : vec3(0.0);
}
