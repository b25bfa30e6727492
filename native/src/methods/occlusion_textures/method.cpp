// How the occlusion_textures method runs for one light: fit, slice, pre-filter, shade, name layers.
// SPDX-License-Identifier: GPL-3.0-or-later
// Paper 4: Eisemann and Décoret, occlusion textures (docs/methods/occlusion_textures.md).
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "methods/method.h"
#include "methods/occlusion_textures/passes.h"
#include "scene_cache/scene_cache.h"
#include "scene_cache/moved_region.h"

namespace ss {

namespace {

constexpr SettingSpec kSlices = intSetting("slices", 8, 1, 16, "slices the occluders are cut into");
constexpr SettingSpec kResolution =
    intSetting("resolution", 512, 16, 4096, "long side of the occlusion textures in texels");
constexpr SettingSpec kFilter = choiceSetting(
    "filter", "sat|mipmap|nbuffer", "pre-filter of the slices (sat: exact, and the fastest on llvmpipe)");
constexpr SettingSpec kThinFix =
    flagSetting("thin_fix", false, "thin-object fix on every mesh (off: only meshes flagged thin)");
constexpr SettingSpec kFade = choiceSetting("fade", "below|paper", "how a slice's occlusion fades with depth");
constexpr SettingSpec kSlicing = choiceSetting(
    "slicing", "perspective|orthographic", "slice projection (orthographic: the paper's figure 4's worse one)");
// Tests only: shade every slice, to show that skipping the empty ones changes nothing.
constexpr SettingSpec kSkipEmptySlices = flagSetting("debug.skip_empty_slices", true, "skip empty slices");
// The benchmark's per-stage times: wait for the GPU at each stage boundary.
constexpr SettingSpec kFinishStages = flagSetting("debug.finish_stages", false, "glFinish at each stage");

class OcclusionTexturesMethod final : public Method {
public:
    OcclusionTexturesMethod()
        : Method("occlusion_textures", MethodDevice::Gl,
                 {kSlices, kResolution, kFilter, kThinFix, kFade, kSlicing, kSkipEmptySlices, kFinishStages}) {}

    Layers render(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        int sliceCount = settings.integer(kSlices);
        int resolution = settings.integer(kResolution);
        occlusion::Filter filter = occlusion::parseFilter(settings.choice(kFilter));
        occlusion::Fade fade = settings.choice(kFade) == "below" ? occlusion::Fade::Below : occlusion::Fade::Paper;
        bool thinFixAll = settings.flag(kThinFix);
        occlusion::Projection projection = settings.choice(kSlicing) == "perspective"
                                               ? occlusion::Projection::Perspective
                                               : occlusion::Projection::Orthographic;
        bool skipEmptySlices = settings.flag(kSkipEmptySlices);
        bool finishStages = settings.flag(kFinishStages);
        auto stage = [&](float fraction, const char* name) {
            if (finishStages) sceneCache.gl().Finish();
            settings.report(fraction, name);
        };

        stage(0.1f, "slicing");
        const occlusion::SliceSetup& setup =
            slicesFor(sceneCache, lightIndex, SlicesKey{sliceCount, resolution, filter, thinFixAll, projection});
        stage(0.4f, "pre-filtering");
        occlusion::FilteredSlices filtered = occlusion::prefilter(filter, kept_.at(lightIndex)->slices);
        stage(0.6f, "shading");
        occlusion::ShadeOutput out = occlusion::shade(sceneCache, lightIndex, setup, filtered, fade, settings.extraLayers,
                                                      skipEmptySlices);
        stage(1.0f, "done");

        Layers layers;
        layers.add("V", std::move(out.visibility));
        layers.add("mask", std::move(out.mask));
        if (settings.extraLayers)
            for (size_t k = 0; k < out.slices.size(); ++k) layers.add("slice_" + std::to_string(k), std::move(out.slices[k]));
        return layers;
    }

private:
    // The settings that shape the slices.
    struct SlicesKey {
        int sliceCount = 0, resolution = 0;
        occlusion::Filter filter{};
        bool thinFixAll = false;
        occlusion::Projection projection{};
        bool operator==(const SlicesKey&) const = default;
    };
    struct KeptSlices {
        SlicesKey key;
        Scene::LightGeometryKey geometry;     // what they show
        std::vector<MeshPlacement> drawn;     // where each mesh was then
        occlusion::SliceSetup setup;
        occlusion::SliceTextures slices;
    };

    // The slices see the occluders from the light, so a camera edit (an orbit, another view) or
    // another light's edit keeps them, and moves that leave their fit as it was redraw them only
    // where the moved meshes were and are. The pre-filter runs on every render: the SAT tables
    // live in a scratch texture other renders share.
    const occlusion::SliceSetup& slicesFor(SceneCache& sceneCache, int lightIndex, const SlicesKey& key) {
        const Scene& scene = sceneCache.scene();
        const Scene::LightGeometryKey geometry = scene.lightGeometryKey(lightIndex);
        // Lights removed since (indices past the last) go with their textures.
        kept_.erase(kept_.lower_bound(int(scene.lights().size())), kept_.end());
        std::optional<KeptSlices>& kept = kept_[lightIndex];
        if (kept && kept->key == key && kept->geometry == geometry) {
            ++stats_.lightWorkKept;
            return kept->setup;
        }
        occlusion::KernelLight kernel = occlusion::kernelLight(sceneCache.light(lightIndex), scene.bounds());
        occlusion::SliceSetup setup =
            occlusion::fitSlices(scene, kernel, key.sliceCount, key.resolution, key.projection, lightIndex);
        std::vector<MeshPlacement> now = sceneCache.placements();
        Scene::LightGeometryKey earlier = kept ? kept->geometry : Scene::LightGeometryKey{};
        earlier.geometryVersion = geometry.geometryVersion;  // everything but the meshes the same?
        if (kept && kept->key == key && earlier == geometry && kept->setup == setup) {
            if (std::optional<std::vector<Bounds>> boxes = movedBoxes(kept->drawn, now)) {
                if (std::optional<PixelRect> rect = boxesOnScreen(*boxes, setup.worldToClip, setup.width, setup.height)) {
                    if (!rect->empty()) occlusion::patchSlices(sceneCache, setup, kept->slices, key.thinFixAll, *rect);
                    kept->geometry = geometry;
                    kept->drawn = std::move(now);
                    ++stats_.lightWorkPatched;
                    return kept->setup;
                }
            }
        }
        kept.reset();  // its textures are freed before the new ones are made
        occlusion::SliceTextures slices = occlusion::renderSlices(sceneCache, setup, key.filter, key.thinFixAll);
        kept = KeptSlices{key, geometry, std::move(now), std::move(setup), std::move(slices)};
        ++stats_.lightWorkMade;
        return kept->setup;
    }

    // Each light's last slices, by light index (a few MiB each at the default 8 slices of 512²;
    // freed with the renderer's scene cache, on the render thread).
    std::map<int, std::optional<KeptSlices>> kept_;
};

}  // namespace

std::unique_ptr<Method> makeOcclusionTexturesMethod() { return std::make_unique<OcclusionTexturesMethod>(); }

}  // namespace ss
