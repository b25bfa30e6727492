// How the C API writes render results as one multilayer EXR.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "capi/capi_internal.h"
#include "core/names.h"
#include "io/exr_file.h"
#include "io/pass_names.h"

using namespace ss::capi;

namespace {

// OpenEXR cuts longer channel names, and cut names collide.
constexpr size_t kMaxChannelBytes = 255;

}  // namespace

extern "C" {

SS_API ss_status ss_write_exr(const char* path, const char* view_layer,
                              const ss_result* const* results, int32_t result_count) {
    return guarded([&] {
        require(path, "ss_write_exr", "path");
        if (result_count <= 0)
            ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_write_exr: there are no results to write to '" +
                                                    std::string(path) + "'");
        require(results, "ss_write_exr", "results");
        std::string layer = view_layer ? view_layer : "ViewLayer";
        ss::checkViewLayerName(layer);
        std::vector<ss::ExrPassRef> passes;
        for (int32_t i = 0; i < result_count; ++i) {
            const ss_result* r = results[i];
            if (!r)
                ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_write_exr: results[" + std::to_string(i) + "] is null");
            for (const auto& [name, image] : r->layers.items) {
                std::string pass = ss::passName(r->light, r->method, name);
                if (ss::channelName(layer, pass).size() > kMaxChannelBytes)
                    ss::fail(SS_ERROR_INVALID_ARGUMENT,
                             "ss_write_exr: channel " + ss::quoted(ss::channelName(layer, pass)) +
                                 " is longer than EXR's " + std::to_string(kMaxChannelBytes) + " bytes");
                passes.push_back({pass, &image});
            }
        }
        ss::writeMultilayerExr(path, layer, passes);
    });
}

}  // extern "C"
