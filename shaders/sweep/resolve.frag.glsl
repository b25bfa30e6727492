// How a camera pixel gets the sweep's V and mask: the drawn shadow intensity where the receiver
// plane's mesh is seen and the light reaches it (the visibility contract), lit elsewhere.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/camera_gbuffer.glsl"
#include "common/visibility_contract.glsl"

uniform sampler2D uShadowIntensity;  // r: the shadow mesh's summed intensity at this pixel
uniform int uReceiverMesh;           // the mesh the shadow mesh lies on

layout(location = 0) out vec4 oResult;  // V, mask

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    Surface s = loadSurface(pixel);
    // The shadow mesh is drawn without a depth test: anything in front of the plane took the
    // pixel in the camera pass, which the mesh index says.
    bool onPlane = s.receives && int(texelFetch(uCamIds, pixel, 0).x) == uReceiverMesh;
    if (!onPlane || !lightReaches(s.position, s.normal)) {
        oResult = vec4(1.0, 0.0, 0.0, 0.0);
        return;
    }
    float intensity = texelFetch(uShadowIntensity, pixel, 0).r;
    oResult = vec4(1.0 - clamp(intensity, 0.0, 1.0), 1.0, 0.0, 0.0);
}
