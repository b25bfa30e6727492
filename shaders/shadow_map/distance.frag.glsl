// What the shared light-centre shadow map stores: the caster's distance to the light centre.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/shadow_map.glsl"

in vec3 vWorld;

layout(location = 0) out float oDistance;

void main() {
    oDistance = shadowDistanceOf(vWorld);
}
