// How a see-through mesh's vertex reaches the every-triangle camera pass (the test's reference
// pass): common/mesh.vert.glsl's arithmetic, from the unindexed see-through buffers.
// SPDX-License-Identifier: GPL-3.0-or-later
uniform mat4 uWorldToClip;
#include "common/mesh_placement.glsl"
#include "common/see_through_vertex.glsl"

out vec3 vWorld;

void main() {
    vWorld = meshToWorld(seeThroughVertex());
    gl_Position = uWorldToClip * vec4(vWorld, 1.0);
}
