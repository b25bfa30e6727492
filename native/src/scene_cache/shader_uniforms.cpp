// How the uniforms of the shared shader includes are set: placement, light, camera pass, shadow
// map, see-through material.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/shader_uniforms.h"

#include <cmath>

#include "scene_cache/scene_cache.h"

namespace ss {

void setPlacementUniforms(const gl::Program& program, const GpuMesh& m) {
    program.set("uTransformed", m.transformed ? 1 : 0);
    program.set("uObjectToWorld", m.objectToWorld);
    program.set("uNormalToWorld", m.normalToWorld);
}

void setShadowMapUniforms(const gl::Program& program, const ShadowMap& map) {
    program.set("uShadowWorldToClip", map.worldToClip());
    program.set("uShadowOrigin", map.origin);
    program.set("uShadowAxis", map.axis);
    program.set("uShadowOrthographic", map.orthographic ? 1 : 0);
    program.set("uShadowSize", float(map.size));
    program.set("uShadowTexelScale", map.orthographic ? 2.0f * map.halfWidth / float(map.size)
                                                      : 2.0f * map.tanHalfFov / float(map.size));
}

void setAlphaMaterialUniforms(const gl::Program& program, const GpuSeeThrough::Material& material,
                              uint32_t index) {
    program.set("uAlphaMaterial", index);
    program.set("uAlphaTextured", material.textured ? 1 : 0);
    program.set("uAlphaConstant", material.constant);
    if (material.textured) program.setTexture("uAlphaTexture", kAlphaTextureUnit, material.texture.id());
}

int SceneCache::bindShadowMap(const gl::Program& program, const ShadowMap& map, int unit) const {
    program.setTexture("uShadowDistance", unit, map.distance.id());
    setShadowMapUniforms(program, map);
    return unit + 1;
}

int SceneCache::bindCameraPass(const gl::Program& program, int firstUnit) {
    const CameraPass& pass = cameraPass();
    program.setTexture("uCamPositionDepth", firstUnit, pass.positionDepth());
    program.setTexture("uCamNormalReceive", firstUnit + 1, pass.normalReceive());
    program.setTexture("uCamIds", firstUnit + 2, pass.ids());
    return firstUnit + 3;
}

void SceneCache::setLightUniforms(const gl::Program& program, int lightIndex) const {
    const Light& L = light(lightIndex);
    program.set("uLight.type", int(L.type));
    program.set("uLight.position", L.position());
    program.set("uLight.direction", L.direction());
    program.set("uLight.halfAxisX", L.isArea() ? L.halfAxisX() : glm::vec3(0.0f));
    program.set("uLight.halfAxisY", L.isArea() ? L.halfAxisY() : glm::vec3(0.0f));
    program.set("uLight.radius", L.radius);
    program.set("uLight.equivalentRadius", L.equivalentRadius());
    program.set("uLight.cosHalfSpot", std::cos(0.5f * L.spotSize));
    program.set("uLight.sinHalfSun", std::sin(L.sunHalfAngle()));
}

}  // namespace ss
