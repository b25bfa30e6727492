// How the hard shadow from the light centre is resolved over the camera pass (the baseline method).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>

#include "core/error.h"
#include "gl/render_state.h"
#include "gl/scratch_targets.h"
#include "methods/method.h"
#include "methods/sparse_check.h"
#include "scene_cache/scene_cache.h"

namespace ss {

namespace {

// Bias, in world sizes of one shadow-map texel at the receiver's distance:
//   constant 1.0  absorbs rasterisation and 32F rounding of the stored distance;
//   slope    1.0  x tan(theta): with nearest sampling the texel centre lies up to sqrt(2)/2
//                 texel from the receiver point, and on a surface tilted by theta from the
//                 light direction the distance changes by tan(theta) per unit of that offset.
// tan(theta) is capped at 20 (theta ~ 87 deg) so grazing receivers are not lit straight through.
// The shader also looks up from the normal-offset point (shadowLookupPoint): the slope term sees
// the receiver's own face, not the steeper neighbouring facet a terminator texel holds.
// Settings "bias" and "slope_bias" override both; "shadow_map_size" the map (default 2048).
constexpr SettingSpec kConstantBias = floatSetting("bias", 1.0, 0.0, 1000.0, "constant depth bias in texels");
constexpr SettingSpec kSlopeBias = floatSetting("slope_bias", 1.0, 0.0, 1000.0, "depth bias per unit of tan(slope), in texels");

class ShadowMapMethod final : public Method {
public:
    ShadowMapMethod() : Method("shadow_map", MethodDevice::Gl, {kShadowMapSizeSetting, kConstantBias, kSlopeBias}) {}

    Layers render(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        const gl::Functions& g = sceneCache.gl();
        settings.report(0.0f, "shadow map");
        const CameraPass& cam = sceneCache.cameraPass();
        const ShadowMap& map = sceneCache.shadowMap(lightIndex, shadowMapSizeSetting(settings));
        settings.report(0.5f, "resolve");

        gl::Framebuffer& out = gl::scratchFramebuffer("shadow_map.camera", cam.width, cam.height, {GL_RGBA32F});
        out.bind();
        gl::apply(gl::states::overwrite);
        const gl::Program& p = gl::program("common/fullscreen.vert.glsl", "shadow_map/resolve.frag.glsl");
        p.use();
        int unit = sceneCache.bindCameraPass(p);
        sceneCache.bindShadowMap(p, map, unit);
        sceneCache.setLightUniforms(p, lightIndex);
        p.set("uConstantBias", settings.number(kConstantBias));
        p.set("uSlopeBias", settings.number(kSlopeBias));
        sceneCache.drawFullscreen();
        g.BindFramebuffer(GL_FRAMEBUFFER, 0);
        g.check("resolving the shadow map");

        std::vector<Image> ch = out.readChannels(0, settings.extraLayers ? 3 : 2);
        Layers layers;
        layers.add("V", std::move(ch[0]));
        layers.add("mask", std::move(ch[1]));
        if (settings.extraLayers) layers.add("light_distance", std::move(ch[2]));
        settings.report(1.0f, "done");
        return layers;
    }

    // V is 0 or 1: each checked pixel is off by at least min(V, 1 - V) of the truth.
    double errorLowerBound(const SparseCheck& check, const Scene& scene, int lightIndex) const override {
        (void)scene, (void)lightIndex;
        return checkedLowerBound(check, [](const PixelVisibility& p) {
            const double v = p.visibility;
            return std::min(v, 1.0 - v);
        });
    }
};

}  // namespace

std::unique_ptr<Method> makeShadowMapMethod() { return std::make_unique<ShadowMapMethod>(); }

}  // namespace ss
