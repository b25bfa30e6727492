// What the float-blending probe draws: one constant colour (gl/capabilities.cpp).
// SPDX-License-Identifier: GPL-3.0-or-later
uniform vec4 uValue;
layout(location = 0) out vec4 oColor;

void main() { oColor = uValue; }
