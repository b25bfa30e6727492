// What the `sweep` method is: geometric soft shadows on a planar receiver from light samples,
// sweep-line outlines, rings and a triangulated penumbra (paper 2), drawn into the camera view.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "core/error.h"
#include "methods/method.h"
#include "methods/sparse_check.h"
#include "methods/sweep/receiver.h"
#include "methods/sweep/lookup.h"
#include "methods/sweep/raster.h"
#include "methods/sweep/shadow.h"
#include "scene_cache/scene_cache.h"
#include "core/visibility_contract.h"

namespace ss {

namespace {

// What drawSweepShadow() gives, computed on the CPU: one lookup per cluster's mesh, their weighted
// intensities added.
Layers lookUpSweepShadow(const CameraImages& cam, const Light& light, const SweepShadow& shadow) {
    const int w = cam.width, h = cam.height;
    Image V(w, h, 1.0f), mask(w, h, 0.0f);
    std::vector<ShadowLookup> lookups;
    if (shadow.parts.empty()) lookups.emplace_back(shadow.mesh);
    else
        for (const planar::ShadowMesh& part : shadow.parts) lookups.emplace_back(part);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            size_t i = cam.index(x, y);
            // Pixels that do not see the receiver plane are outside this method's mask.
            if (!cam.covered(x, y) || !cam.receives(x, y) || int(cam.ids[i].x) != shadow.plane.mesh) continue;
            glm::vec3 P = cam.position(x, y);
            if (!lightReaches(light, P, cam.normal(x, y))) continue;
            mask.at(x, y) = 1.0f;
            glm::dvec2 q = shadow.plane.toPlane(glm::dvec3(P));
            double gx = (q.x - shadow.plane.cu) * shadow.snap.scale();
            double gy = (q.y - shadow.plane.cv) * shadow.snap.scale();
            float intensity = 0.0f;
            for (const ShadowLookup& l : lookups) intensity += l.intensity(gx, gy);
            // std::clamp keeps a NaN: a broken shadow mesh shows as V = NaN, which the
            // finiteness tests catch, instead of passing for lit.
            V.at(x, y) = 1.0f - std::clamp(intensity, 0.0f, 1.0f);
        }
    Layers layers;
    layers.add("V", std::move(V));
    layers.add("mask", std::move(mask));
    return layers;
}

class SweepMethod final : public Method {
public:
    // GL for the shared camera pass and for drawing the shadow mesh; the mesh is CPU geometry.
    SweepMethod() : Method("sweep", MethodDevice::Gl, sweepSettings()) {}

    void prepare(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        shadowFor(sceneCache.scene(), lightIndex, settings);
    }

    Layers render(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        const SweepShadow& shadow = shadowFor(sceneCache.scene(), lightIndex, settings);
        std::string raster = settings.choice(kSweepRaster);
        settings.report(0.5f, "sweep: camera pass");
        Layers layers = raster == "gl" ? drawSweepShadow(sceneCache, shadow, lightIndex)
                                       : lookUpSweepShadow(sceneCache.cameraImages(), sceneCache.light(lightIndex), shadow);
        settings.report(1.0f, "sweep: done");
        return layers;
    }

    // V is 1 on every surface but its receiver plane's mesh (at the default settings): off by
    // 1 - V there.
    double errorLowerBound(const SparseCheck& check, const Scene& scene, int lightIndex) const override {
        int plane = -1;
        try {
            plane = findReceiverPlane(scene, scene.light(lightIndex), "").mesh;
        } catch (const Error& e) {
            if (e.status() != SS_ERROR_UNSUPPORTED) throw;
            return 0.0;  // no plane to shade: the render says so, not the bound
        }
        if (plane < 0) return 0.0;
        return checkedLowerBound(check, [plane](const PixelVisibility& p) {
            const double v = p.visibility;
            return p.mesh == plane ? 0.0 : 1.0 - v;
        });
    }

private:
    struct Key {
        Scene::LightGeometryKey geometry;
        int samples = 0, clusters = 1, passes = 1;  // passes 0: auto
        uint32_t seed = 0;
        double border = 0;
        planar::FillMode fill{};
        std::string receiver;
        bool weights = true;
        bool operator==(const Key&) const = default;
    };

    const SweepShadow& shadowFor(const Scene& scene, int lightIndex, const RenderSettings& settings) {
        SweepOptions o = sweepOptions(settings);
        Key k{scene.lightGeometryKey(lightIndex), o.samples, o.clusters, o.passes, o.seed, o.borderShare, o.fill,
              o.receiver, o.irradianceWeights};
        // Automatic passes follow the camera (an orbit or a zoom can widen the penumbra on
        // screen), but only a change of the count they come to makes the shadow again.
        const bool passesChanged = cached_ && o.passes == 0 && scene.hasCamera() &&
                                   autoSweepPasses(cached_->widest, scene.camera(), o.samples) != cached_->passes;
        if (!cached_ || !(key_ == k) || passesChanged) {
            settings.report(0.0f, "sweep: geometry");
            cached_.reset();  // its memory is free before the new shadow is made
            cached_ = computeSweepShadow(scene, lightIndex, o, &projections_);
            key_ = k;
            ++stats_.lightWorkMade;
        } else {
            ++stats_.lightWorkKept;
        }
        return *cached_;
    }

    Key key_;
    std::optional<SweepShadow> cached_;
    // Each occluder's projections per light: a move or an edit projects that mesh again only.
    SweepProjectionCache projections_;
};

}  // namespace

std::unique_ptr<Method> makeSweepMethod() { return std::make_unique<SweepMethod>(); }

}  // namespace ss
