// What the shared shader includes (shaders/common/) read, set from a mesh's placement, a shadow
// map or a see-through material; SceneCache's binders (bindCameraPass, setLightUniforms,
// bindShadowMap) are defined beside them (shader_uniforms.cpp).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>

#include "gl/program.h"
#include "scene_cache/gpu_mesh.h"
#include "scene_cache/see_through.h"
#include "scene_cache/shadow_map.h"

namespace ss {

// The texture unit of a see-through material's alpha texture ("common/see_through.glsl").
inline constexpr int kAlphaTextureUnit = 15;

// Sets the uniforms of "common/mesh_placement.glsl" for mesh `m`.
void setPlacementUniforms(const gl::Program& program, const GpuMesh& m);
// Sets uShadow* of "common/shadow_map.glsl" (all but the texture: bindShadowMap binds it too).
void setShadowMapUniforms(const gl::Program& program, const ShadowMap& map);
// Sets the material uniforms of "common/see_through.glsl" for material `index` of a mesh.
void setAlphaMaterialUniforms(const gl::Program& program, const GpuSeeThrough::Material& material,
                              uint32_t index);

}  // namespace ss
