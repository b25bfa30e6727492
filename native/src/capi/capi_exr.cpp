// How the C API writes render results as one multilayer EXR.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "capi/capi_internal.h"
#include "io/exr_file.h"
#include "io/pass_names.h"

using namespace ss::capi;

extern "C" {

SS_API ss_status ss_write_exr(const char* path, const char* view_layer,
                              const ss_result* const* results, int32_t result_count) {
    return guarded([&] {
        require(path, "ss_write_exr", "path");
        if (result_count <= 0)
            ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_write_exr: there are no results to write to '" +
                                                    std::string(path) + "'");
        require(results, "ss_write_exr", "results");
        std::vector<ss::ExrPassRef> passes;
        std::string methods;  // "<pass>=<method that ran>;..."
        for (int32_t i = 0; i < result_count; ++i) {
            const ss_result* r = results[i];
            if (!r)
                ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_write_exr: results[" + std::to_string(i) + "] is null");
            for (const auto& [layer, image] : r->layers.items)
                passes.push_back({ss::passName(r->light, r->requested, layer), &image});
            methods += (methods.empty() ? "" : ";") + ss::passName(r->light, r->requested, "V") + "=" + r->method;
        }
        ss::writeMultilayerExr(path, view_layer ? view_layer : "ViewLayer", passes, methods);
    });
}

}  // extern "C"
