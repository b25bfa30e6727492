// How pcss and penumbra_map set up their shared shadow-map comparison and draw their camera pass.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/receiver_plane.h"

#include <algorithm>

#include "gl/render_state.h"
#include "gl/scratch_targets.h"

namespace ss {

glm::mat3 shadowRayBasis(const ShadowMap& map) {
    // Rows of the view matrix are the map's right, up and backward axes in world space.
    glm::vec3 right(map.worldToLight[0][0], map.worldToLight[1][0], map.worldToLight[2][0]);
    glm::vec3 up(map.worldToLight[0][1], map.worldToLight[1][1], map.worldToLight[2][1]);
    float s = map.orthographic ? map.halfWidth : map.tanHalfFov;
    return glm::mat3(right * s, up * s, map.axis);
}

void setShadowRayBasis(const gl::Program& program, const ShadowMap& map) {
    glm::mat3 b = shadowRayBasis(map);
    // Program::set has no mat3 overload; the glsl mat3 is set through its location.
    GLint loc = program.location("uShadowRayBasis");
    if (loc >= 0) gl::api().ProgramUniformMatrix3fv(program.id(), loc, 1, GL_FALSE, &b[0][0]);
}

const gl::Framebuffer& drawReceiverPlanePass(SceneCache& sceneCache, int lightIndex, const ShadowMap& map, const char* target,
                                             const char* fragment, const glm::vec4& clear,
                                             const std::function<void(const gl::Program&, int firstFreeUnit)>& setInputs) {
    const CameraPass& cam = sceneCache.cameraPass();
    const gl::Framebuffer& out = gl::scratchFramebuffer(target, cam.width, cam.height, {GL_RGBA32F});
    out.bind();
    out.clearColor(0, clear);
    gl::apply(gl::states::overwrite);
    const gl::Program& p = gl::program("common/fullscreen.vert.glsl", fragment);
    p.use();
    int unit = sceneCache.bindCameraPass(p, 0);
    unit = sceneCache.bindShadowMap(p, map, unit);
    sceneCache.setLightUniforms(p, lightIndex);
    setShadowRayBasis(p, map);
    setInputs(p, unit);
    sceneCache.drawFullscreen();
    sceneCache.gl().check(fragment);
    sceneCache.gl().BindFramebuffer(GL_FRAMEBUFFER, 0);
    return out;
}

Layers readReceiverPlaneLayers(const gl::Framebuffer& out, bool extraLayers,
                               std::initializer_list<std::pair<const char*, int>> extra) {
    Layers layers;
    std::vector<Image> ch = out.readChannels(0, extraLayers ? 4 : 2);
    layers.add("V", std::move(ch[0]));
    layers.add("mask", std::move(ch[1]));
    if (extraLayers)
        for (const auto& [name, channel] : extra) layers.add(name, std::move(ch[size_t(channel)]));
    return layers;
}

float nearestCasterDistance(const Scene& scene, int lightIndex, const ShadowMap& map) {
    float best = map.farPlane;
    for (size_t i = 0; i < scene.meshes().size(); ++i) {
        if (!scene.castsFor(int(i), lightIndex)) continue;
        for (const glm::vec3& p : scene.meshes()[i].positions) {
            float d = map.distanceOf(p);
            if (d > 0.0f) best = std::min(best, d);
        }
    }
    return std::max(best, map.nearPlane);
}

}  // namespace ss
