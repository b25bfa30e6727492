// What a sweep shadow-mesh fragment writes: its Gouraud-interpolated shadow intensity.
// SPDX-License-Identifier: GPL-3.0-or-later
in float vIntensity;

layout(location = 0) out vec4 oIntensity;

void main() {
    oIntensity = vec4(clamp(vIntensity, 0.0, 1.0), 1.0, 0.0, 0.0);
}
