// What the `reference` method is: Embree ray-traced visibility, the truth every method is measured by.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <memory>

#include "methods/method.h"
#include "scene_cache/scene_cache.h"
#include "reference/render_reference.h"

namespace ss {
namespace {

// CPU only: needs no GL, reads nothing from the scene cache but its scene and its Embree BVH
// (kept per scene id and geometry version, shared with refinement and the sparse check), so
// rendering every light of an unchanged scene builds the BVH once.
class ReferenceMethod final : public Method {
public:
    ReferenceMethod() : Method("reference", MethodDevice::Cpu, referenceSettings()) {}
    Layers render(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) override {
        return renderReference(sceneCache.scene(), lightIndex, settings, &sceneCache.traceScenes());
    }
};

}  // namespace

std::unique_ptr<Method> makeReferenceMethod() { return std::make_unique<ReferenceMethod>(); }

}  // namespace ss
