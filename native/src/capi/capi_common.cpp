// How the C API reports its version and last error, and copies text out to callers.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstring>

#include "capi/capi_internal.h"
#include "core/method_names.h"
#include "io/atomic_file.h"

namespace ss::capi {

namespace {
thread_local std::string lastError;
thread_local int callbackDepth = 0;
}

ProgressCallbackScope::ProgressCallbackScope() { ++callbackDepth; }
ProgressCallbackScope::~ProgressCallbackScope() { --callbackDepth; }

void refuseInsideProgressCallback(const char* function) {
    if (callbackDepth > 0)
        ss::fail(SS_ERROR_INVALID_ARGUMENT,
                 std::string(function) + ": called from a progress callback (allowed there: "
                                         "reading results and scenes, ss_last_error; not rendering, "
                                         "destroying a context or shutting down)");
}

void setLastError(const std::string& message) {
    try {
        lastError = message;
    } catch (...) {
        // Out of memory while reporting: keep whatever was there.
    }
}

void clearLastError() { lastError.clear(); }

void copyOut(const std::string& text, char* buffer, size_t bufferSize, const char* function) {
    require(buffer, function, "buffer");
    if (text.size() + 1 > bufferSize)
        ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string(function) + ": the buffer holds " +
                                                std::to_string(bufferSize) + " bytes but " +
                                                std::to_string(text.size() + 1) + " are needed");
    std::memcpy(buffer, text.c_str(), text.size() + 1);
}

}  // namespace ss::capi

extern "C" {

SS_API const char* ss_version(void) { return SS_VERSION; }

SS_API void ss_remove_temporary_files(void) { ss::removeTemporaryFiles(); }
SS_API int32_t ss_remove_temporary_files_on_signals(void) { return ss::removeTemporaryFilesOnSignals(); }

SS_API const char* ss_last_error(void) { return ss::capi::lastError.c_str(); }

SS_API int32_t ss_method_count(void) { return int32_t(ss::methodNames().size()); }

SS_API const char* ss_method_name(int32_t index) {
    const auto& names = ss::methodNames();
    if (index < 0 || size_t(index) >= names.size()) return nullptr;
    return names[size_t(index)].c_str();
}

SS_API void ss_render_options_default(ss_render_options* options) {
    if (!options) return;
    *options = ss_render_options{};
    options->samples = 0;
    options->seed = 1;
    options->extra_layers = 1;
    options->progress = nullptr;
    options->progress_user = nullptr;
    options->settings = nullptr;
    options->round = nullptr;
    options->round_user = nullptr;
    options->refine = SS_REFINE_OFF;
    options->refine_rounds = 0;
}

}  // extern "C"
