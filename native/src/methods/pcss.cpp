// How percentage-closer soft shadows (Fernando 2005) are rendered over the shared passes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.h"
#include "gl/framebuffer.h"
#include "gl/render_state.h"
#include "gl/scratch_targets.h"
#include "methods/method.h"
#include "methods/receiver_plane.h"
#include "scene_cache/scene_cache.h"

namespace ss {

namespace {

constexpr SettingSpec kBlockerSamples = intSetting("blocker_samples", 16, 1, 1024, "shadow-map taps of the blocker search");
constexpr SettingSpec kPcfSamples = [] {
    SettingSpec s = intSetting("pcf_samples", 32, 1, 4096, "taps of the filter");
    s.renderDefault = "the render's samples, or 32";
    return s;
}();
constexpr SettingSpec kMaxSearch =
    floatSetting("max_search", 0.25, 0.0, 1.0, "largest blocker search radius, a share of the shadow map");

class PcssMethod final : public Method {
public:
    PcssMethod()
        : Method("pcss", MethodDevice::Gl, {kBlockerSamples, kPcfSamples, kShadowMapSizeSetting, kMaxSearch}) {}

    Layers render(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        const Light& light = sceneCache.light(lightIndex);
        if (settings.samples > 4096)
            fail(SS_ERROR_INVALID_ARGUMENT, "pcss: samples must be in 1..4096 (got " + std::to_string(settings.samples) + ")");
        const int blockerSamples = settings.integer(kBlockerSamples);
        const int pcfSamples = settings.integer(kPcfSamples, settings.samples > 0 ? settings.samples : 32);
        const int mapSize = shadowMapSizeSetting(settings);
        const float maxSearch = settings.number(kMaxSearch);

        const ShadowMap& map = sceneCache.shadowMap(lightIndex, mapSize);
        sceneCache.cameraPass();  // the shared pass drawn (or found) before the filter stage begins
        settings.report(0.3f, "pcss filter");

        const gl::Framebuffer& out = drawReceiverPlanePass(
            sceneCache, lightIndex, map, "pcss.camera", "pcss/camera.frag.glsl", glm::vec4(1.0f, 0.0f, 0.0f, 0.0f),
            [&](const gl::Program& p, int) {
                p.set("uBlockerSamples", blockerSamples);
                p.set("uPcfSamples", pcfSamples);
                // A sun's size is an angle: the penumbra grows by tan(half angle) per unit of distance.
                p.set("uLightSize", light.type == LightType::Sun ? std::tan(light.sunHalfAngle())
                                                                 : light.equivalentRadius());
                p.set("uNearCaster", nearestCasterDistance(sceneCache.scene(), lightIndex, map));
                p.set("uMaxSearchUv", maxSearch);
            });
        return readReceiverPlaneLayers(out, settings.extraLayers, {{"blocker_distance", 2}, {"kernel_texels", 3}});
    }

};

}  // namespace

std::unique_ptr<Method> makePcssMethod() { return std::make_unique<PcssMethod>(); }

}  // namespace ss
