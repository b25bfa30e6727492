// The camera pass as drawn from every triangle of each mesh (one indexed draw per mesh, the
// triangle from gl_PrimitiveID): the reference the listed-triangle pass must equal bit for bit.
// Same outputs and arithmetic as shaders/camera/gbuffer.frag.glsl; with SEE_THROUGH, the same
// alpha test (drawn by SceneCache::drawSeeThroughWhere, unindexed: gl_PrimitiveID is still the triangle).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/mesh_placement.glsl"
#ifdef SEE_THROUGH
#include "common/see_through.glsl"
#endif

in vec3 vWorld;

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
    int triangle = gl_PrimitiveID;
    vec3 n = meshNormalToWorld(faceNormal[triangle].xyz);
    vec3 toEye = uOrthographic != 0 ? -uCameraForward : uCameraPosition - vWorld;
    if (dot(n, toEye) < 0.0) n = -n;
    float viewDepth = -(uWorldToView * vec4(vWorld, 1.0)).z;
    oPositionDepth = vec4(vWorld, max(viewDepth, 1e-30));
    oNormalReceive = vec4(n, uReceives);
    oIds = vec4(float(uMeshIndex), float(triangle), 0.0, 0.0);
}
