// How a scene mesh vertex reaches clip space for any pass (camera, shadow map, method passes).
// SPDX-License-Identifier: GPL-3.0-or-later
layout(location = 0) in vec3 aPosition;  // world space

uniform mat4 uWorldToClip;

out vec3 vWorld;

void main() {
    vWorld = aPosition;
    gl_Position = uWorldToClip * vec4(aPosition, 1.0);
}
