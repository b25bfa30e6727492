// Where a vertex of a see-through mesh is and which UV and material it carries: drawn unindexed
// (three vertices per triangle, SceneCache::drawSeeThroughWhere), fetched from the mesh's own index,
// position, corner-UV and material buffers.
// SPDX-License-Identifier: GPL-3.0-or-later
layout(std430, binding = 2) readonly buffer MeshIndices { uint meshIndex[]; };       // uint32 x3 per triangle
layout(std430, binding = 3) readonly buffer MeshPositions { float meshPosition[]; };  // vec3 per vertex, packed
layout(std430, binding = 4) readonly buffer CornerUvs { vec2 cornerUv[]; };           // 3 per triangle
layout(std430, binding = 5) readonly buffer TriangleMaterials { uint triangleMaterial[]; };

out vec2 vAlphaUv;
flat out uint vAlphaMaterial;

// The object-space position of this vertex; sets vAlphaUv and vAlphaMaterial.
vec3 seeThroughVertex() {
    uint triangle = uint(gl_VertexID) / 3u;
    uint v = meshIndex[uint(gl_VertexID)];
    vAlphaUv = cornerUv[uint(gl_VertexID)];
    vAlphaMaterial = triangleMaterial[triangle];
    return vec3(meshPosition[3u * v], meshPosition[3u * v + 1u], meshPosition[3u * v + 2u]);
}
