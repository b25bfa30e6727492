// How the C API creates, describes and shuts down GL contexts (the library's render threads).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <string>
#include <string_view>

#include "capi/capi_internal.h"
#include "core/libstdcxx_baseline.h"
#include "gl/render_thread.h"
#include "renderer/cache_stats.h"

using namespace ss::capi;

namespace ss::capi {

ContextUse::ContextUse(ss_context& context) : context_(context) {
    std::lock_guard lock(context.m);
    if (context.closing)
        ss::fail(SS_ERROR_INVALID_ARGUMENT, "the context is being destroyed (ss_context_destroy)");
    ++context.callsInFlight;
}

ContextUse::~ContextUse() {
    std::lock_guard lock(context_.m);
    if (--context_.callsInFlight == 0) {
        if (!context_.closing) context_.stopRenders = false;
        context_.idle.notify_all();
    }
}

}  // namespace ss::capi

extern "C" {

SS_API ss_status ss_context_create(ss_backend backend, ss_context** out) {
    return guarded([&] {
        require(out, "ss_context_create", "out");
        *out = nullptr;
        if (backend != SS_BACKEND_AUTO && backend != SS_BACKEND_EGL && backend != SS_BACKEND_OSMESA)
            ss::fail(SS_ERROR_INVALID_ARGUMENT,
                     "ss_context_create: unknown backend " + std::to_string(int(backend)));
        *out = new ss_context(backend);
    });
}

SS_API void ss_context_destroy(ss_context* context) {
    // Refused (the context stays alive) rather than deadlocking on its own render.
    guarded([&] {
        if (!context) return;
        refuseInsideProgressCallback("ss_context_destroy");
        {
            std::unique_lock lock(context->m);
            context->closing = true;
            context->stopRenders = true;  // renders in flight stop at their next check
            context->idle.wait(lock, [&] { return context->callsInFlight == 0; });
        }
        delete context;
    });
}

SS_API void ss_context_cancel_renders(ss_context* context) {
    guarded([&] {
        if (!context) return;
        std::lock_guard lock(context->m);
        if (context->callsInFlight > 0) context->stopRenders = true;
    });
}

SS_API ss_status ss_context_info(const ss_context* context, char* buffer, size_t buffer_size) {
    return guarded([&] {
        require(context, "ss_context_info", "context");
        refuseInsideProgressCallback("ss_context_info");
        // info() starts GL lazily, which changes the renderer but not what the caller sees.
        ContextUse use(*const_cast<ss_context*>(context));
        std::string info = const_cast<ss_context*>(context)->renderer.info();
        copyOut(info, buffer, buffer_size, "ss_context_info");
    });
}

SS_API int32_t ss_cache_stat_count(void) { return int32_t(ss::kCacheStatCount); }

SS_API const char* ss_cache_stat_name(int32_t index) {
    if (index < 0 || size_t(index) >= ss::kCacheStatCount) return nullptr;
    return ss::kCacheStats[index].name;
}

SS_API const char* ss_cache_stat_doc(int32_t index) {
    if (index < 0 || size_t(index) >= ss::kCacheStatCount) return nullptr;
    return ss::kCacheStats[index].doc;
}

SS_API ss_status ss_context_cache_stat(const ss_context* context, const char* name, double* out) {
    return guarded([&] {
        require(context, "ss_context_cache_stat", "context");
        require(name, "ss_context_cache_stat", "name");
        require(out, "ss_context_cache_stat", "out");
        refuseInsideProgressCallback("ss_context_cache_stat");
        const ss::CacheStatInfo* stat = nullptr;
        std::string names;
        for (const ss::CacheStatInfo& s : ss::kCacheStats) {
            if (std::string_view(s.name) == name) stat = &s;
            names += (names.empty() ? "" : ", ") + std::string(s.name);
        }
        if (!stat)
            ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string("ss_context_cache_stat: unknown cache stat '") + name +
                                                    "'; the stats are " + names);
        ContextUse use(*const_cast<ss_context*>(context));
        *out = stat->value(context->renderer.cacheStats());
    });
}

SS_API void ss_shutdown(void) {
    guarded([] {
        refuseInsideProgressCallback("ss_shutdown");
        ss::shutdownRenderThreads();
    });
}

}  // extern "C"
