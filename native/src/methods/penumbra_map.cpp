// How penumbra maps (Wyman and Hansen 2003) are rendered: the shared shadow map (pass 1), cones
// and sheets into the penumbra map (pass 2), and the camera lookup (pass 3).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.h"
#include "geometry/cones_sheets.h"
#include "geometry/silhouette.h"
#include "gl/framebuffer.h"
#include "gl/render_state.h"
#include "gl/scratch_targets.h"
#include "methods/method.h"
#include "methods/penumbra_map.h"
#include "methods/receiver_plane.h"
#include "methods/sparse_check.h"
#include "scene_cache/scene_cache.h"

namespace ss {

// The light radius penumbra_map models: a sphere (point, spot) or the area-equal disk of an
// area light (Light::equivalentRadius()), seen face-on from every occluder.
float penumbraMapLightRadius(const Light& light) { return light.equivalentRadius(); }

// The cones and sheets of every casting mesh for one light and shadow map.
ConesSheets buildPenumbraGeometry(const Scene& scene, int lightIndex, const ShadowMap& map, float radius,
                                  const ConeSheetSettings& settings) {
    PenumbraLight pl;
    pl.centre = map.origin;
    pl.axis = map.axis;
    pl.radius = radius;
    pl.nearDepth = map.nearPlane;
    pl.farDepth = map.farPlane;
    ConesSheets all;
    for (size_t i = 0; i < scene.meshes().size(); ++i) {
        if (!scene.castsFor(int(i), lightIndex)) continue;
        const Mesh& mesh = scene.meshes()[i];
        PointSilhouette sil = pointSilhouette(mesh, map.origin);
        all.append(buildConesSheets(mesh, sil, pl, settings));
    }
    return all;
}

namespace {

constexpr SettingSpec kConeSegments = intSetting("cone_segments", 16, 3, 256, "segments of each vertex's penumbra cone");
constexpr SettingSpec kIntensity =
    choiceSetting("intensity", "coverage|paper", "penumbra intensity: the light's covered share, or the paper's ramp");
// The benchmark: wait for each pass so progress reports time the stages.
constexpr SettingSpec kFinishStages = flagSetting("debug.finish_stages", false, "glFinish at each pass");

}  // namespace

PenumbraIntensity intensityRule(const RenderSettings& settings) {
    return settings.choice(kIntensity) == "coverage" ? PenumbraIntensity::Coverage : PenumbraIntensity::Paper;
}

namespace {

// Cones and sheets on the GPU, kept while the light's geometry key (Scene::lightGeometryKey)
// and the parameters stay the same: a camera edit keeps them.
struct GpuConesSheets {
    Scene::LightGeometryKey key;
    float radius = -1.0f;
    int mapSize = 0;
    int coneSegments = 0;
    size_t cones = 0, sheets = 0;
    GLsizei indexCount = 0;
    gl::VertexArrayHandle vao;
    gl::BufferHandle vertices, indices;
};

class PenumbraMapMethod final : public Method {
public:
    PenumbraMapMethod()
        : Method("penumbra_map", MethodDevice::Gl,
                 {kShadowMapSizeSetting, kConeSegments, kIntensity, kFinishStages}) {}

    // V is 0 wherever the light centre is hidden (the umbra is the centre's hard shadow): off by
    // the truth's V there.
    double errorLowerBound(const SparseCheck& check, const Scene& scene, int lightIndex) const override {
        (void)scene, (void)lightIndex;
        return checkedLowerBound(check, [](const PixelVisibility& p) {
            const double v = p.visibility;
            return p.centreVisible ? 0.0 : v;
        });
    }

    void prepare(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        const Light& light = sceneCache.light(lightIndex);
        if (light.type == LightType::Sun)
            fail(SS_ERROR_UNSUPPORTED, "penumbra_map: light '" + light.name +
                                           "' is a sun; penumbra maps need a light centre (use pcss)");
        const int mapSize = shadowMapSizeSetting(settings);
        ConeSheetSettings cs;
        cs.coneSegments = settings.integer(kConeSegments);
        (void)intensityRule(settings);  // a bad value fails before any GL work
        const float radius = penumbraMapLightRadius(light);
        GpuConesSheets& g = geometry_;
        const Scene& scene = sceneCache.scene();
        if (g.key == scene.lightGeometryKey(lightIndex) && g.radius == radius && g.mapSize == mapSize && g.coneSegments == cs.coneSegments)
            return;
        const ShadowMap& map = sceneCache.shadowMap(lightIndex, mapSize);
        settings.report(0.1f, "penumbra_map cones and sheets");
        ConesSheets cpu = buildPenumbraGeometry(sceneCache.scene(), lightIndex, map, radius, cs);
        const gl::Functions& api = sceneCache.gl();
        g = GpuConesSheets{};
        g.key = scene.lightGeometryKey(lightIndex);
        g.radius = radius;
        g.mapSize = mapSize;
        g.coneSegments = cs.coneSegments;
        g.cones = cpu.cones();
        g.sheets = cpu.sheets();
        g.indexCount = GLsizei(cpu.triangles.size() * 3);
        if (g.indexCount == 0) return;
        g.vertices = gl::makeBuffer(cpu.vertices.data(), cpu.vertices.size() * sizeof(ConeSheetVertex));
        g.indices = gl::makeBuffer(cpu.triangles.data(), cpu.triangles.size() * sizeof(glm::uvec3));
        GLuint vao = 0;
        api.CreateVertexArrays(1, &vao);
        g.vao = gl::VertexArrayHandle(vao);
        static_assert(sizeof(ConeSheetVertex) == 4 * sizeof(float));
        api.VertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, sizeof(ConeSheetVertex));
        api.VertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, 0);
        api.VertexArrayAttribBinding(vao, 0, 0);
        api.EnableVertexArrayAttrib(vao, 0);
        api.VertexArrayElementBuffer(vao, g.indices.id());
        api.check("uploading penumbra_map cones and sheets");
    }

    Layers render(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        const gl::Functions& api = sceneCache.gl();
        const ShadowMap& map = sceneCache.shadowMap(lightIndex, geometry_.mapSize);
        sceneCache.cameraPass();  // the shared pass drawn (or found) before the stages are timed
        const bool finishStages = settings.flag(kFinishStages);

        // Pass 2: the penumbra map, cleared to lit; darkest fragment wins through LESS.
        settings.report(0.3f, "penumbra_map pass 2");
        const gl::Framebuffer& pm =
            gl::scratchFramebuffer("penumbra_map.map", map.size, map.size, {GL_R32F}, GL_DEPTH_COMPONENT32F);
        pm.bind();
        pm.clearColor(0, glm::vec4(1.0f));
        pm.clearDepth(1.0f);
        if (geometry_.indexCount > 0) {
            // Cone bases lie on the far plane: clamp rather than clip them there.
            gl::apply(gl::states::opaqueDepthClamped);
            const gl::Program& p = gl::program("penumbra_map/cones.vert.glsl", "penumbra_map/cones.frag.glsl");
            p.use();
            sceneCache.bindShadowMap(p, map, 0);
            p.set("uIntensityRule", int(intensityRule(settings)));
            api.BindVertexArray(geometry_.vao.id());
            api.DrawElements(GL_TRIANGLES, geometry_.indexCount, GL_UNSIGNED_INT, nullptr);
            api.BindVertexArray(0);
            api.check("penumbra_map pass 2");
        }
        if (finishStages) api.Finish();

        // Pass 3: the camera lookup.
        settings.report(0.7f, "penumbra_map pass 3");
        const gl::Framebuffer& out = drawReceiverPlanePass(
            sceneCache, lightIndex, map, "penumbra_map.camera", "penumbra_map/camera.frag.glsl",
            glm::vec4(1.0f, 0.0f, 0.0f, 1.0f),
            [&](const gl::Program& p, int unit) { p.setTexture("uPenumbraMap", unit, pm.colorId(0)); });
        if (finishStages) api.Finish();
        settings.report(0.9f, "penumbra_map readback");
        return readReceiverPlaneLayers(out, settings.extraLayers, {{"penumbra_map", 3}, {"hard_shadow", 2}});
    }

    // For tests and the benchmark: how many cones and sheets the last prepare() built.
    size_t cones() const { return geometry_.cones; }
    size_t sheets() const { return geometry_.sheets; }

private:
    GpuConesSheets geometry_;
};

}  // namespace

std::unique_ptr<Method> makePenumbraMapMethod() { return std::make_unique<PenumbraMapMethod>(); }

}  // namespace ss
