// What "a GL context" is to the library, whichever backend made it (EGL or OSMesa).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <memory>
#include <string>

#include "softshadow/softshadow.h"

namespace ss::gl {

// A 4.5 core context with no window. Created, made current, used and destroyed on ONE thread
// (the render thread): never make it current on the host's (Blender's) thread.
class Context {
public:
    virtual ~Context() = default;
    virtual const char* backendName() const = 0;  // "egl" or "osmesa"
    virtual void makeCurrent() = 0;
    virtual void releaseCurrent() = 0;
    virtual void* getProcAddress(const char* name) const = 0;
};

// Each throws ss::Error(SS_ERROR_GL) saying why the backend is unusable (library missing,
// no display, no 4.5 core context...). Defined in egl_context.cpp / osmesa_context.cpp, the only
// files that include EGL or OSMesa headers.
std::unique_ptr<Context> createEglContext();
std::unique_ptr<Context> createOsmesaContext();

// "egl", "osmesa", "auto"; throws ss::Error(SS_ERROR_INVALID_ARGUMENT) for another value.
const char* backendName(ss_backend backend);

}  // namespace ss::gl
