// `auto`: which methods it tries for a light, how it scores them, and which one it keeps.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "core/settings.h"
#include "methods/method.h"
#include "methods/sparse_check.h"

namespace ss {

// `auto`'s settings: its own (how many pixels the sparse check traces and with how many light
// samples), then every key of the methods it may try (all but the reference), in method order.
// A key shared by methods has one entry (kShadowMapSizeSetting), so it is checked once.
const SettingTable& autoSettingTable();
// What a candidate renders with: `settings` with only the keys of its table (`candidate`, the
// method's own), so each candidate takes the user's settings it has and its defaults for the rest.
RenderSettings candidateSettings(const RenderSettings& settings, const SettingTable& candidate);
struct AutoCheckSize {
    int pixels = 0, samples = 0;  // pixels 0: no check, choose by the light's shape
};
AutoCheckSize autoCheckSize(const RenderSettings& settings, const Camera& camera);

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

// What `auto` did for one render: the candidates it rendered (each at full size, in the order
// rendered), those its prior left out (autoPriorKeeps) and those whose lower bound on the
// check (Method::errorLowerBound) already lost to a rendered one.
struct AutoTrials {
    std::vector<std::string> rendered, skippedByPrior, skippedByBound;
};

// How `auto` reaches the methods: the scene's method object of a name (for its lower bound), and
// a candidate's layers at the settings given (throwing SS_ERROR_UNSUPPORTED where the method
// cannot take the scene: sweep without a planar receiver, penumbra_map with the light on it).
struct AutoMethods {
    std::function<const Method&(const std::string& name)> method;
    std::function<Layers(const std::string& name, const RenderSettings& settings)> render;
};
struct AutoChoice {
    std::string method;
    Layers layers;
};

// The candidates the prior keeps render first, each with candidateSettings, then those whose lower
// bound leaves them a chance; the one whose estimate against `check` is lowest is kept (the
// cheaper on a tie). With no check (null), the method by the light's shape. Fails with
// SS_ERROR_UNSUPPORTED when no candidate can render the light.
AutoChoice chooseAutoMethod(const Scene& scene, int lightIndex, const RenderSettings& settings,
                            const SparseCheck* check, const AutoMethods& methods, AutoTrials& trials);

}  // namespace ss
