// How a casting triangle reaches the slicing camera: clip position and depth below the light.
// SPDX-License-Identifier: GPL-3.0-or-later
#version 450 core
layout(location = 0) in vec3 aPosition;  // object space (ss::GpuMesh)
#include "common/mesh_placement.glsl"

uniform mat4 worldToClip;   // the offset slicing camera (centre of projection d behind the light)
uniform mat4 worldToLight;  // light-local: x, y in the light plane, z = depth below it

// 1: a plane that cannot shadow (SliceSetup::unsliced), dropped by putting it beyond the far plane.
uniform int unsliced;

out float lightDepth;

void main() {
    vec3 position = meshToWorld(aPosition);
    lightDepth = (worldToLight * vec4(position, 1.0)).z;
    gl_Position = unsliced != 0 ? vec4(0.0, 0.0, 2.0, 1.0) : worldToClip * vec4(position, 1.0);
}
