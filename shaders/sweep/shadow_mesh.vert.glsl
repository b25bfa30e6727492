// How a sweep shadow-mesh vertex (on the receiver plane, with its intensity) reaches the camera.
// SPDX-License-Identifier: GPL-3.0-or-later
layout(location = 0) in vec3 aPosition;   // world space, on the receiver plane
layout(location = 1) in float aIntensity; // 0 lit .. 1 umbra

uniform mat4 uWorldToClip;

out float vIntensity;

void main() {
    vIntensity = aIntensity;
    gl_Position = uWorldToClip * vec4(aPosition, 1.0);
}
