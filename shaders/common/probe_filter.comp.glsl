// What the compute/filtering probe measures: a linear sample halfway between two R32F texels.
// SPDX-License-Identifier: GPL-3.0-or-later
layout(local_size_x = 1) in;
uniform sampler2D uTexture;
layout(std430, binding = 0) buffer Result { float result; };

void main() { result = textureLod(uTexture, vec2(0.5, 0.5), 0.0).r; }
