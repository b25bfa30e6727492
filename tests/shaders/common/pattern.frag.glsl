// What the GL self-tests draw: each pixel's own window coordinates, so a read-back shows the
// row order and the pixel centres (tests/native/test_gl_context.cpp).
// SPDX-License-Identifier: GPL-3.0-or-later
layout(location = 0) out vec4 oColor;
uniform float uTag;

void main() { oColor = vec4(gl_FragCoord.xy, uTag, 1.0); }
