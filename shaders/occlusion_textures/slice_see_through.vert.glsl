// How a see-through caster's vertex reaches the slicing camera (slice.vert.glsl's arithmetic,
// from the unindexed see-through buffers).
// SPDX-License-Identifier: GPL-3.0-or-later
#version 450 core
#include "common/mesh_placement.glsl"
#include "common/see_through_vertex.glsl"

uniform mat4 worldToClip;
uniform mat4 worldToLight;

// 1: a plane that cannot shadow (SliceSetup::unsliced), dropped by putting it beyond the far plane.
uniform int unsliced;

out float lightDepth;

void main() {
    vec3 position = meshToWorld(seeThroughVertex());
    lightDepth = (worldToLight * vec4(position, 1.0)).z;
    gl_Position = unsliced != 0 ? vec4(0.0, 0.0, 2.0, 1.0) : worldToClip * vec4(position, 1.0);
}
