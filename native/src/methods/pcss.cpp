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
#include "frame/frame.h"

namespace ss {

namespace {

class PcssMethod final : public Method {
public:
    const char* name() const override { return "pcss"; }
    bool needsGl() const override { return true; }
    std::vector<std::string> settingKeys() const override { return {"blocker_samples", "pcf_samples", "shadow_map_size", "max_search"}; }

    Layers render(Frame& frame, int lightIndex, const RenderSettings& settings) override {
        const Light& light = frame.light(lightIndex);
        if (settings.samples > 4096)
            fail(SS_ERROR_INVALID_ARGUMENT, "pcss: samples must be in 1..4096 (got " + std::to_string(settings.samples) + ")");
        const int blockerSamples = settings.integer("blocker_samples", 16, 1, 1024);
        const int pcfSamples = settings.integer("pcf_samples", settings.samples > 0 ? settings.samples : 32, 1, 4096);
        const int mapSize = settings.integer("shadow_map_size", 0, 0, 16384);
        const float maxSearch = settings.number("max_search", 0.25f, 0.0f, 1.0f);

        const ShadowMap& map = frame.shadowMap(lightIndex, mapSize);
        const CameraPass& cam = frame.cameraPass();
        settings.report(0.3f, "pcss filter");

        const gl::Framebuffer& out = gl::scratchFramebuffer("pcss.camera", cam.width, cam.height, {GL_RGBA32F});
        out.bind();
        out.clearColor(0, glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
        gl::apply(gl::states::overwrite);
        const gl::Program& p = gl::program("common/fullscreen.vert.glsl", "pcss/camera.frag.glsl");
        p.use();
        int unit = frame.bindCameraPass(p, 0);
        frame.bindShadowMap(p, map, unit);
        frame.setLightUniforms(p, lightIndex);
        setShadowRayBasis(p, map);
        p.set("uBlockerSamples", blockerSamples);
        p.set("uPcfSamples", pcfSamples);
        // A sun's size is an angle: the penumbra grows by tan(half angle) per unit of distance.
        p.set("uLightSize", light.type == LightType::Sun ? std::tan(light.sunHalfAngle())
                                                         : light.equivalentRadius());
        p.set("uNearCaster", nearestCasterDistance(frame.scene(), map));
        p.set("uMaxSearchUv", maxSearch);
        frame.drawFullscreen();
        frame.gl().check("pcss camera pass");

        Layers layers;
        std::vector<Image> ch = out.readChannels(0, settings.extraLayers ? 4 : 2);
        layers.add("V", std::move(ch[0]));
        layers.add("mask", std::move(ch[1]));
        if (settings.extraLayers) {
            layers.add("blocker_distance", std::move(ch[2]));
            layers.add("kernel_texels", std::move(ch[3]));
        }
        frame.gl().BindFramebuffer(GL_FRAMEBUFFER, 0);
        return layers;
    }

private:
    // The output target, kept between renders of the same frame.
};

}  // namespace

std::unique_ptr<Method> makePcssMethod() { return std::make_unique<PcssMethod>(); }

}  // namespace ss
