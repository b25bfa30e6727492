// How the GL function table is filled from a context's loader and reached from the render thread.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/gl_functions.h"

#include <string>

#include "core/error.h"

namespace ss::gl {

namespace {
thread_local const Functions* tCurrent = nullptr;
}

void Functions::load(const std::function<void*(const char*)>& getProcAddress) {
#define SS_GL_FUNCTION(type, name) name = reinterpret_cast<type>(getProcAddress("gl" #name));
#include "gl/gl_function_list.h"
#undef SS_GL_FUNCTION
    // A few functions every part of the library uses: their absence means no usable 4.5 context.
    const std::pair<const char*, const void*> required[] = {
        {"glGetString", reinterpret_cast<const void*>(GetString)},
        {"glGetIntegerv", reinterpret_cast<const void*>(GetIntegerv)},
        {"glCreateShader", reinterpret_cast<const void*>(CreateShader)},
        {"glGenFramebuffers", reinterpret_cast<const void*>(GenFramebuffers)},
        {"glTexStorage2D", reinterpret_cast<const void*>(TexStorage2D)},
        {"glDrawElements", reinterpret_cast<const void*>(DrawElements)},
        {"glReadPixels", reinterpret_cast<const void*>(ReadPixels)},
        {"glCreateTextures", reinterpret_cast<const void*>(CreateTextures)},
        {"glDispatchCompute", reinterpret_cast<const void*>(DispatchCompute)},
    };
    for (auto& [name, ptr] : required)
        if (!ptr) fail(SS_ERROR_GL, std::string("GL function ") + name + " could not be loaded");
}

const char* errorName(GLenum error) {
    switch (error) {
        case GL_NO_ERROR: return "GL_NO_ERROR";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
        case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    }
    return "unknown GL error";
}

void Functions::check(const char* what) const {
    GLenum first = GetError();
    if (first == GL_NO_ERROR) return;
    // Drain the queue so the next check reports only what happens after this one.
    for (int i = 0; i < 16 && GetError() != GL_NO_ERROR; ++i) {
    }
    fail(SS_ERROR_GL, std::string(what) + ": " + errorName(first));
}

const Functions* current() { return tCurrent; }
void setCurrent(const Functions* functions) { tCurrent = functions; }

const Functions& api() {
    if (!tCurrent)
        fail(SS_ERROR_GL, "no GL context of the library is current on this thread "
                          "(GL work must run on the render thread)");
    return *tCurrent;
}

}  // namespace ss::gl
