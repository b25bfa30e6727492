// Which GL functions the library calls: one table of pointers per context, loaded by name.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <GL/glcorearb.h>

#include <functional>

namespace ss::gl {

// Every core GL 1.0-4.5 entry point as a member named without the "gl" prefix, so
// `glGenBuffers(1, &b)` is written `gl.GenBuffers(1, &b)` (glad's multi-context style).
// Loaded from eglGetProcAddress / OSMesaGetProcAddress: libepoxy and glvnd's libOpenGL
// silently do nothing under an OSMesa context, so nothing here goes through them.
struct Functions {
#define SS_GL_FUNCTION(type, name) type name = nullptr;
#include "gl/gl_function_list.h"
#undef SS_GL_FUNCTION

    // Throws ss::Error(SS_ERROR_GL) naming the first function that a 4.5 core context must
    // have but the loader did not return.
    void load(const std::function<void*(const char*)>& getProcAddress);

    // Throws ss::Error(SS_ERROR_GL) with `what` and the GL error name when glGetError reports one.
    void check(const char* what) const;
};

// The table of the context current on this thread (the render thread), or null elsewhere.
const Functions* current();
void setCurrent(const Functions* functions);

// Like current() but throws ss::Error(SS_ERROR_GL) when this thread has no context of ours.
const Functions& api();

const char* errorName(GLenum error);

}  // namespace ss::gl
