// What the camera pass writes per pixel: world position + view depth, facing normal + receive
// flag, mesh and triangle ids (the layout is documented at ss::CameraPass). With SEE_THROUGH, the
// fragments of the material drawn now where its alpha is below the camera's threshold are
// discarded: the camera sees what lies behind a cut-out's holes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/mesh_placement.glsl"
#ifdef SEE_THROUGH
#include "common/see_through.glsl"
#endif

in vec3 vWorld;
flat in int vTriangle;  // index within the mesh (camera/gbuffer.vert.glsl)

layout(std430, binding = 0) readonly buffer FaceNormals { vec4 faceNormal[]; };

uniform mat4 uWorldToView;
uniform vec3 uCameraPosition;
uniform vec3 uCameraForward;
uniform int uOrthographic;
uniform int uMeshIndex;
uniform float uReceives;

layout(location = 0) out vec4 oPositionDepth;
layout(location = 1) out vec4 oNormalReceive;
layout(location = 2) out vec4 oIds;

void main() {
#ifdef SEE_THROUGH
    cameraAlphaTest(seeThroughAlpha());
#endif
    // The face normal from the mesh (exact), not from derivatives (noisy at grazing angles).
    int triangle = vTriangle;
    vec3 n = meshNormalToWorld(faceNormal[triangle].xyz);
    vec3 toEye = uOrthographic != 0 ? -uCameraForward : uCameraPosition - vWorld;
    if (dot(n, toEye) < 0.0) n = -n;
    float viewDepth = -(uWorldToView * vec4(vWorld, 1.0)).z;
    oPositionDepth = vec4(vWorld, max(viewDepth, 1e-30));
    oNormalReceive = vec4(n, uReceives);
    oIds = vec4(float(uMeshIndex), float(triangle), 0.0, 0.0);
}
