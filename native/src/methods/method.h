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
#include "frame/cache_counters.h"

namespace ss {

class Frame;  // frame/frame.h: the scene plus the GL passes shared by every method

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
    virtual void prepare(Frame& frame, int lightIndex, const RenderSettings& settings) {
        (void)frame, (void)lightIndex, (void)settings;
    }
    // Produces at least "V" and "mask"; with settings.extraLayers, the method's debug layers too
    // (never "umbra"/"penumbra": the renderer adds those, core/visibility_classes.h). Every
    // layer: camera resolution, row 0 = top.
    virtual Layers render(Frame& frame, int lightIndex, const RenderSettings& settings) = 0;
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
// The methods `auto` renders and scores against the sparse check (methods/sparse_check.h), in
// the order of their cost (cheapest first): the GL methods whose assumptions the scene keeps.
std::vector<std::string> autoCandidates(const Scene& scene, int lightIndex);
// `auto`'s prior, which of the candidates are worth rendering at all: the general methods, and the
// one whose paper models the light's shape (dbuffer for disk, ellipse, point and spot lights,
// occlusion_textures for square and rectangular ones); each of the two is left out under the
// other shapes, where it models a light it is not given (docs/methods/README.md).
bool autoPriorKeeps(const Scene& scene, int lightIndex, const std::string& method);
// `auto`'s fallback where the sparse check cannot run: a method by the light's shape
// (docs/methods/README.md).
std::string chooseAutoMethodByShape(const Scene& scene, int lightIndex);

}  // namespace ss
