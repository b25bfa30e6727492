// How a full-screen pass covers the viewport: one triangle from gl_VertexID, no vertex buffer.
// SPDX-License-Identifier: GPL-3.0-or-later
out vec2 vUv;  // 0..1 over the viewport, GL orientation (v = 0 at the bottom row)

void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    vUv = p;
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
