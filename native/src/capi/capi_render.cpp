// How the C API renders one (light, method) and hands out the resulting layers.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "capi/capi_internal.h"
#include "methods/method.h"

#include <limits>

using namespace ss::capi;

extern "C" {

SS_API ss_status ss_render(ss_context* context, const ss_scene* scene, int32_t light_index,
                           const char* method, const ss_render_options* options, ss_result** out) {
    return guarded([&] {
        require(out, "ss_render", "out");
        *out = nullptr;
        refuseInsideProgressCallback("ss_render");
        require(context, "ss_render", "context");
        require(scene, "ss_render", "scene");
        require(method, "ss_render", "method");
        const ss::Light& light = scene->scene.light(light_index, "ss_render");
        ss::RenderSettings settings = renderSettingsFrom(options, "ss_render", &context->stopRenders);
        ContextUse use(*context);
        auto result = std::make_unique<ss_result>();
        result->light = light.name;
        result->requested = method;
        ss::Renderer::AutoTrials trials;
        std::vector<std::string> warnings;
        ss_render_options defaults;
        ss_render_options_default(&defaults);
        const ss_render_options& given = options ? *options : defaults;
        ss::Renderer::RoundFn rounds;
        if (given.round)
            rounds = [&](ss::Renderer::RoundResult& r) {
                ss_result partial;
                partial.layers = std::move(r.layers);
                partial.method = r.method;
                partial.requested = method;
                partial.light = light.name;
                partial.estimatedRmse = r.estimatedRmse;
                ProgressCallbackScope inside;
                return given.round(given.round_user, &partial, r.round, r.rounds) == 0;
            };
        result->layers = context->renderer.render(scene->scene, light_index, method, settings, &result->method,
                                                  &result->estimatedRmse, &trials, &warnings, rounds);
        for (const std::string& w : warnings) result->warnings += w + "\n";
        if (!trials.rendered.empty()) result->methodsRendered = int32_t(trials.rendered.size());
        if (result->method.empty()) result->method = method;
        *out = result.release();
    });
}

SS_API void ss_result_destroy(ss_result* result) {
    guarded([&] { delete result; });
}

SS_API const char* ss_result_method(const ss_result* result) {
    return result ? result->method.c_str() : nullptr;
}

SS_API double ss_result_estimated_rmse(const ss_result* result) {
    return result ? result->estimatedRmse : std::numeric_limits<double>::quiet_NaN();
}

SS_API int32_t ss_result_methods_rendered(const ss_result* result) {
    return result ? result->methodsRendered : 0;
}

SS_API const char* ss_result_warnings(const ss_result* result) {
    return result ? result->warnings.c_str() : nullptr;
}

SS_API const char* ss_result_light(const ss_result* result) {
    return result ? result->light.c_str() : nullptr;
}

SS_API int32_t ss_result_layer_count(const ss_result* result) {
    return result ? int32_t(result->layers.items.size()) : 0;
}

SS_API ss_status ss_result_layer(const ss_result* result, int32_t index, const char** name,
                                 const float** pixels, int32_t* width, int32_t* height) {
    return guarded([&] {
        require(result, "ss_result_layer", "result");
        const auto& items = result->layers.items;
        const auto& [layerName, image] =
            items[ss::checkedIndex(index, items.size(), "ss_result_layer", "layer", "layers", "result")];
        if (name) *name = layerName.c_str();
        if (pixels) *pixels = image.pixels.data();
        if (width) *width = image.width;
        if (height) *height = image.height;
    });
}

}  // extern "C"
