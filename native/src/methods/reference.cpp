// What the `reference` method is: Embree ray-traced visibility, the truth every method is measured by.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <memory>

#include "methods/method.h"
#include "frame/frame.h"
#include "reference/render_reference.h"
#include "reference/trace_scene_cache.h"

namespace ss {
namespace {

// CPU only: needs no GL, reads nothing from the frame but its scene. The Embree scene is cached
// inside the method object per (scene id, revision), so rendering every light of an unchanged
// scene builds the BVH once.
class ReferenceMethod final : public Method {
public:
    ReferenceMethod() : Method("reference", MethodDevice::Cpu, referenceSettingKeys()) {}
    Layers render(Frame& frame, int lightIndex, const RenderSettings& settings) override {
        return renderReference(frame.scene(), lightIndex, settings, &cache_);
    }

private:
    TraceSceneCache cache_;
};

}  // namespace

std::unique_ptr<Method> makeReferenceMethod() { return std::make_unique<ReferenceMethod>(); }

}  // namespace ss
