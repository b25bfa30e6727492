// How a see-through caster's vertex reaches the slicing camera (slice.vert.glsl's arithmetic,
// from the unindexed see-through buffers).
// SPDX-License-Identifier: GPL-3.0-or-later
#version 450 core
#include "common/mesh_placement.glsl"
#include "common/see_through_vertex.glsl"

uniform mat4 worldToClip;
uniform mat4 worldToLight;

out float lightDepth;

void main() {
    vec3 position = meshToWorld(seeThroughVertex());
    lightDepth = (worldToLight * vec4(position, 1.0)).z;
    gl_Position = worldToClip * vec4(position, 1.0);
}
