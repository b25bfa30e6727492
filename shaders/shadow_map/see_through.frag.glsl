// The shared shadow map's distance for a see-through caster: kept where the hashed alpha test
// keeps the fragment (a cut-out's holes are never in the map; 50 % alpha covers half its texels).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/shadow_map.glsl"
#include "common/see_through.glsl"

in vec3 vWorld;

layout(location = 0) out float oDistance;

void main() {
    alphaHashedTest(seeThroughAlpha());
    oDistance = shadowDistanceOf(vWorld);
}
