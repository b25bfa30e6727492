// What the `reference` method is: Embree ray-traced visibility, the truth every method is measured by.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <memory>

#include "core/error.h"
#include "methods/method.h"
#include "reference/render_reference.h"
#include "reference/trace_scene_cache.h"
#if __has_include("pipeline/frame.h")
#include "pipeline/frame.h"
#define SS_REFERENCE_HAS_FRAME 1
#endif

namespace ss {
namespace {

// CPU only: needs no GL, reads nothing from the frame but its scene. The Embree scene is cached
// inside the method object per (scene id, revision), so rendering every light of an unchanged
// scene builds the BVH once.
class ReferenceMethod final : public Method {
public:
    const char* name() const override { return "reference"; }
    bool needsGl() const override { return false; }
    Layers render(Frame& frame, int lightIndex, const RenderSettings& settings) override {
#ifdef SS_REFERENCE_HAS_FRAME
        return renderReference(frame.scene(), lightIndex, settings, &cache_);
#else
        (void)frame, (void)lightIndex, (void)settings;
        fail(SS_ERROR_UNSUPPORTED, "reference: built without pipeline/frame.h");
#endif
    }

private:
    TraceSceneCache cache_;
};

}  // namespace

std::unique_ptr<Method> makeReferenceMethod() { return std::make_unique<ReferenceMethod>(); }

}  // namespace ss
