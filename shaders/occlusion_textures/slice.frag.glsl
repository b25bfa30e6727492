// How an opaque caster's fragment marks its slice as occluded.
// SPDX-License-Identifier: GPL-3.0-or-later
#version 450 core
#include "occlusion_textures/slice_write.glsl"

void main() {
    writeSlice(1.0);
}
