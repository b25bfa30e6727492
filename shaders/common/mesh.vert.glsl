// How a scene mesh vertex reaches clip space for any pass (camera, shadow map, method passes).
// SPDX-License-Identifier: GPL-3.0-or-later
layout(location = 0) in vec3 aPosition;  // object space (ss::GpuMesh)

uniform mat4 uWorldToClip;
#include "common/mesh_placement.glsl"

out vec3 vWorld;

void main() {
    vWorld = meshToWorld(aPosition);
    gl_Position = uWorldToClip * vec4(vWorld, 1.0);
}
