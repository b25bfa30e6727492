// What the C API's opaque handles hold, and how every C function turns exceptions into a status.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <exception>
#include <new>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "core/scene.h"
#include "pipeline/renderer.h"
#include "softshadow/softshadow.h"

struct ss_context {
    explicit ss_context(ss_backend b) : renderer(b) {}
    ss::Renderer renderer;
};

struct ss_scene {
    ss::Scene scene;
};

struct ss_result {
    ss::Layers layers;
    std::string method;     // the method that ran ("auto" resolved)
    std::string requested;  // the method asked for: it names the EXR pass, so `auto` stays stable
    std::string light;   // the light's real name
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

// Throws SS_ERROR_INVALID_ARGUMENT naming the parameter when a required pointer is null.
inline void require(const void* pointer, const char* function, const char* parameter) {
    if (!pointer)
        ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + parameter + " is null");
}

// Copies text (with its terminating zero) into a caller's buffer, or fails naming the size needed.
void copyOut(const std::string& text, char* buffer, size_t bufferSize, const char* function);

}  // namespace ss::capi
