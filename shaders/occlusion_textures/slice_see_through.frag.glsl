// How a see-through caster's fragment marks its slice: occluded by its material's alpha (a
// cut-out's holes not at all, a 50 % card by half).
// SPDX-License-Identifier: GPL-3.0-or-later
#version 450 core
#include "occlusion_textures/slice_write.glsl"
#include "common/see_through.glsl"

void main() {
    writeSlice(seeThroughAlpha());
}
