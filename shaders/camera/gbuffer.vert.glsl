// Where each vertex of the camera pass's listed triangles is: the pass draws, per mesh, only the
// triangles that may cover a pixel centre (SceneCache lists them, scene_cache/covering_triangles.h), three
// vertices each, fetched from the mesh's own index and position buffers. The triangle's index
// travels as a flat output instead of gl_PrimitiveID, which would make llvmpipe un-index every
// triangle (its primitive assembler) at about a third of the pass's cost.
// With SEE_THROUGH (a see-through mesh, alpha-tested by the fragment stage) each vertex also
// carries its corner's UV and the triangle's material (ss::GpuSeeThrough's buffers).
// SPDX-License-Identifier: GPL-3.0-or-later
layout(std430, binding = 1) readonly buffer ListedTriangles { uint listedTriangle[]; };
layout(std430, binding = 2) readonly buffer MeshIndices { uint meshIndex[]; };       // uint32 x3 per triangle
layout(std430, binding = 3) readonly buffer MeshPositions { float meshPosition[]; };  // vec3 per vertex, packed

#ifdef SEE_THROUGH
layout(std430, binding = 4) readonly buffer CornerUvs { vec2 cornerUv[]; };           // 3 per triangle
layout(std430, binding = 5) readonly buffer TriangleMaterials { uint triangleMaterial[]; };
out vec2 vAlphaUv;
flat out uint vAlphaMaterial;
#endif

uniform mat4 uWorldToClip;
#include "common/mesh_placement.glsl"

out vec3 vWorld;
flat out int vTriangle;

void main() {
    uint triangle = listedTriangle[gl_VertexID / 3];
    uint corner = 3u * triangle + uint(gl_VertexID % 3);
    uint v = meshIndex[corner];
    vec3 position = vec3(meshPosition[3u * v], meshPosition[3u * v + 1u], meshPosition[3u * v + 2u]);
    // The same arithmetic as common/mesh.vert.glsl: passes that depth-test against the camera
    // pass's depth see the same window depth.
    vWorld = meshToWorld(position);
    gl_Position = uWorldToClip * vec4(vWorld, 1.0);
    vTriangle = int(triangle);
#ifdef SEE_THROUGH
    vAlphaUv = cornerUv[corner];
    vAlphaMaterial = triangleMaterial[triangle];
#endif
}
