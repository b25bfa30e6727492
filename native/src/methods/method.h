// What a shadow method is: prepare (CPU geometry, cacheable) then render (named layers).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/light.h"
#include "core/scene.h"

namespace ss {

class Frame;  // pipeline/frame.h: the scene plus the GL passes shared by every method

// Returns false to cancel. fraction in [0,1].
using ProgressFn = std::function<bool(float fraction, const char* stage)>;

struct RenderSettings {
    int samples = 0;  // 0 = the method's default
    uint32_t seed = 1;
    bool extraLayers = true;
    std::map<std::string, std::string> options;  // method quality settings, "key" -> "value"
    ProgressFn progress;

    // Typed look-ups of `options` with a default; throw ss::Error(SS_ERROR_INVALID_ARGUMENT)
    // naming the key, the value and what is allowed on a malformed value. Numbers are finite.
    float number(const std::string& key, float fallback) const;
    float number(const std::string& key, float fallback, float lo, float hi) const;
    // A whole number in [lo, hi], or `fallback` when absent; `orZero` also allows 0 (the
    // "default" of shadow_map_size and threads).
    int whole(const std::string& key, int fallback, int lo, int hi, bool orZero = false) const;
    bool flag(const std::string& key, bool fallback) const;
    std::string text(const std::string& key, const std::string& fallback) const;
    // Calls progress; throws ss::Error(SS_ERROR_CANCELLED) when it asks to stop.
    void report(float fraction, const char* stage) const;
};

// The shared shadow map's size setting: 0 (Frame's default) or 16..8192 texels.
int shadowMapSizeSetting(const RenderSettings& settings);

// Parses "key=value;key=value" (the C API's settings string).
std::map<std::string, std::string> parseSettings(const std::string& text);

class Method {
public:
    virtual ~Method() = default;
    virtual const char* name() const = 0;
    // True when render() needs the GL device (then it runs on the library's render thread).
    virtual bool needsGl() const = 0;
    // CPU geometry that depends only on the scene and the light. Default: nothing.
    virtual void prepare(Frame& frame, int lightIndex, const RenderSettings& settings) {
        (void)frame, (void)lightIndex, (void)settings;
    }
    // Produces at least "V" and "mask"; with settings.extraLayers, "umbra", "penumbra" and the
    // method's debug layers. Every layer: camera resolution, row 0 = top.
    virtual Layers render(Frame& frame, int lightIndex, const RenderSettings& settings) = 0;
};

// The contract names, in a fixed order.
const std::vector<std::string>& methodNames();
// Throws ss::Error(SS_ERROR_INVALID_ARGUMENT) for an unknown name; "auto" is not accepted here.
std::unique_ptr<Method> createMethod(const std::string& name);
// The documented rule behind "auto" (docs/methods.md).
std::string chooseAutoMethod(const Scene& scene, int lightIndex);

}  // namespace ss
