// What the C API's opaque handles hold, and how every C function turns exceptions into a status.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <atomic>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <new>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "core/scene.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"

// ss_context_destroy may come from another thread while an ss_render on this context runs (the
// add-on's preview stops its worker that way): it sets `closing`, which cancels the render at
// its next check, waits until no call uses the context, and only then deletes it.
// ss_context_cancel_renders sets only `stopRenders` (what the renders check), which clears
// once no call uses the context.
struct ss_context {
    explicit ss_context(ss_backend b) : renderer(b) {}
    ss::Renderer renderer;
    std::atomic<bool> closing{false};
    std::atomic<bool> stopRenders{false};
    std::mutex m;
    std::condition_variable idle;
    int callsInFlight = 0;
};

struct ss_scene {
    ss::Scene scene;
};

struct ss_result {
    ss::Layers layers;
    std::string method;     // the method that ran ("auto" resolved)
    std::string requested;  // the method asked for: it names the EXR pass, so `auto` stays stable
    std::string light;   // the light's real name
    double estimatedRmse = std::numeric_limits<double>::quiet_NaN();  // from the sparse exact check; NaN where none was made
    int32_t methodsRendered = 1;  // auto: the candidates it rendered at full size
    std::string warnings;  // one line per problem the render left out (ss_result_warnings)
};

namespace ss::capi {

void setLastError(const std::string& message);
void clearLastError();

// Runs body; maps ss::Error to its status, bad_alloc and anything else to SS_ERROR_INTERNAL, and
// records the message for ss_last_error(). Nothing escapes into C.
template <class Body>
ss_status guarded(Body&& body) noexcept {
    try {
        body();
        clearLastError();
        return SS_OK;
    } catch (const ss::Error& e) {
        setLastError(e.what());
        return e.status();
    } catch (const std::bad_alloc&) {
        setLastError("out of memory");
        return SS_ERROR_INTERNAL;
    } catch (const std::exception& e) {
        setLastError(std::string("internal error: ") + e.what());
        return SS_ERROR_INTERNAL;
    } catch (...) {
        setLastError("internal error: unknown exception");
        return SS_ERROR_INTERNAL;
    }
}

// Marks one C call as using a context for its lifetime; refuses a context being destroyed.
class ContextUse {
public:
    explicit ContextUse(ss_context& context);
    ~ContextUse();
    ContextUse(const ContextUse&) = delete;
    ContextUse& operator=(const ContextUse&) = delete;

private:
    ss_context& context_;
};

// Throws SS_ERROR_INVALID_ARGUMENT naming the parameter when a required pointer is null.
inline void require(const void* pointer, const char* function, const char* parameter) {
    if (!pointer)
        ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + parameter + " is null");
}

// The progress callback runs while its context is locked: a call back into the library that
// would wait on that lock (ss_render, ss_context_info, ss_context_destroy, ss_shutdown) fails
// instead. ProgressCallbackScope marks the current thread as inside a callback.
struct ProgressCallbackScope {
    ProgressCallbackScope();
    ~ProgressCallbackScope();
};
// Throws SS_ERROR_INVALID_ARGUMENT naming `function` when called from a progress callback.
void refuseInsideProgressCallback(const char* function);

// The one conversion of ss_render_options (null: the defaults) into RenderSettings: negative
// samples refused naming `function`, the settings string parsed, progress wired (marking the
// callback's thread), `cancel` (null: never) the flag the render checks.
ss::RenderSettings renderSettingsFrom(const ss_render_options* options, const char* function,
                                      const std::atomic<bool>* cancel);

// Copies text (with its terminating zero) into a caller's buffer, or fails naming the size needed.
void copyOut(const std::string& text, char* buffer, size_t bufferSize, const char* function);

}  // namespace ss::capi
