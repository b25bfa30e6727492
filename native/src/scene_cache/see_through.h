// What the GPU holds of a see-through mesh's materials (ss::MeshAlpha), for the light-side passes
// that alpha-test their casters (the shared shadow map, occlusion_textures' slices) and for the
// camera pass, which alpha-tests what the camera sees (ss::kCameraAlphaThreshold).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <vector>

#include "core/mesh_alpha.h"
#include "gl/objects.h"

namespace ss {

struct GpuSeeThrough {
    gl::BufferHandle cornerUvs;         // SSBO, vec2 x3 per triangle (zeros where the mesh has none)
    gl::BufferHandle triangleMaterial;  // SSBO, uint per triangle
    struct Material {
        bool textured = false;
        float constant = 1.0f;
        gl::Texture texture;  // R32F alpha, wrap and filter as the material says
    };
    std::vector<Material> materials;
    bool cameraSeesThrough = false;  // MeshAlpha::cameraSeesThrough: the camera pass alpha-tests it
};

// Uploads `alpha` for a mesh of `triangleCount` triangles (needs the GL context current).
GpuSeeThrough uploadSeeThrough(const MeshAlpha& alpha, size_t triangleCount);

}  // namespace ss
