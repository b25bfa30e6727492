// What a shadow method is: prepare (CPU geometry, cacheable) then render (named layers).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/light.h"
#include "core/method_names.h"
#include "core/scene.h"
#include "core/settings.h"
#include "scene_cache/cache_counters.h"

namespace ss {

class SceneCache;  // scene_cache/scene_cache.h: the scene plus the GL passes shared by every method
struct SparseCheck;  // methods/sparse_check.h

// Where a method's render() runs: on the caller's thread, or on the library's GL render thread.
enum class MethodDevice { Cpu, Gl };

// What a method did with its work that depends on the light and the geometry but not on the
// camera (sweep's shadow mesh, occlusion_textures' slices, dbuffer's D-buffer), each time a
// render needed it: made it afresh, took it from the last time under the same
// Scene::lightGeometryKey and settings, or (occlusion_textures after moves) redrew it only where
// the moved meshes were and are.
struct MethodStats {
    SS_METHOD_COUNTERS(SS_COUNTER_MEMBER)
};

class Method {
public:
    // `name`: the contract name (core/method_names.h). `settings`: every key of
    // RenderSettings::options the method reads, with its type, default and range; any other key
    // or a value its entry refuses fails before the method runs (RenderSettings::requireKnownKeys).
    Method(std::string name, MethodDevice device, SettingTable settings)
        : name_(std::move(name)), device_(device), settings_(std::move(settings)) {}
    virtual ~Method() = default;
    const char* name() const { return name_.c_str(); }
    bool needsGl() const { return device_ == MethodDevice::Gl; }
    const SettingTable& settingTable() const { return settings_; }
    // CPU geometry that depends only on the scene and the light. Default: nothing.
    virtual void prepare(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) {
        (void)sceneCache, (void)lightIndex, (void)settings;
    }
    // Produces at least "V" and "mask"; with settings.extraLayers, the method's debug layers too
    // (never "umbra"/"penumbra": the renderer adds those, core/visibility_classes.h). Every
    // layer: camera resolution, row 0 = top.
    virtual Layers render(SceneCache& sceneCache, int lightIndex, const RenderSettings& settings) = 0;
    // What the sparse check says about this method's estimate at its default settings before it
    // renders: a lower bound where its output is constrained (checkedLowerBound). Over the check's
    // own mask; the GL passes and the traced rays may disagree along hard and silhouette edges,
    // so a bound is exact up to that thin band. Default: 0, no bound.
    virtual double errorLowerBound(const SparseCheck& check, const Scene& scene, int lightIndex) const {
        (void)check, (void)scene, (void)lightIndex;
        return 0.0;
    }
    const MethodStats& stats() const { return stats_; }

protected:
    MethodStats stats_;

private:
    std::string name_;
    MethodDevice device_;
    SettingTable settings_;
};

// Throws ss::Error(SS_ERROR_INVALID_ARGUMENT) for an unknown name; "auto" is not accepted here.
std::unique_ptr<Method> createMethod(const std::string& name);

}  // namespace ss
