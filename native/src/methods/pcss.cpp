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
#include "methods/pcss_common.h"
#include "pipeline/frame.h"

namespace ss {

namespace {

int positiveSetting(const RenderSettings& s, const char* key, int fallback, int most) {
    float v = s.number(key, float(fallback));
    if (!(v >= 1.0f) || v > float(most))
        fail(SS_ERROR_INVALID_ARGUMENT, std::string("pcss: setting '") + key + "' must be in 1.." +
                                            std::to_string(most) + " (got " + std::to_string(v) + ")");
    return int(v);
}

class PcssMethod final : public Method {
public:
    const char* name() const override { return "pcss"; }
    bool needsGl() const override { return true; }

    Layers render(Frame& frame, int lightIndex, const RenderSettings& settings) override {
        const Light& light = frame.light(lightIndex);
        const int blockerSamples = positiveSetting(settings, "blocker_samples", 16, 1024);
        const int pcfSamples =
            positiveSetting(settings, "pcf_samples", settings.samples > 0 ? settings.samples : 32, 4096);
        const int mapSize = shadowMapSizeSetting(settings);
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
        Channels ch = splitChannels(out.readRgba(0), out.width(), out.height());
        const Image& v = ch.c[0];
        const Image& mask = ch.c[1];
        layers.add("V", v);
        layers.add("mask", mask);
        if (settings.extraLayers) {
            addClassLayers(layers, v, mask);
            layers.add("blocker_distance", std::move(ch.c[2]));
            layers.add("kernel_texels", std::move(ch.c[3]));
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
