// How an EGL surfaceless 4.5 core context is made (libEGL opened lazily with dlopen).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <dlfcn.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

#include "core/error.h"
#include "gl/context.h"

namespace ss::gl {

namespace {

// The EGL entry points we use, resolved from the dlopen'ed library: linking libEGL would make
// the whole library unloadable on a machine without it.
struct EglApi {
    PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
    PFNEGLINITIALIZEPROC initialize = nullptr;
    PFNEGLBINDAPIPROC bindApi = nullptr;
    PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
    PFNEGLCREATECONTEXTPROC createContext = nullptr;
    PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
    PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
    PFNEGLRELEASETHREADPROC releaseThread = nullptr;
    PFNEGLGETERRORPROC getError = nullptr;
    PFNEGLQUERYSTRINGPROC queryString = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
};

// Opened once and never closed: Blender may hold the same library, and closing it under a
// live display is never needed.
const EglApi& eglApi() {
    static const EglApi api = [] {
        EglApi a;
        void* lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!lib) fail(SS_ERROR_GL, std::string("libEGL.so.1 could not be opened: ") + dlerror());
        a.getProcAddress = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(lib, "eglGetProcAddress"));
        if (!a.getProcAddress) fail(SS_ERROR_GL, "libEGL.so.1 has no eglGetProcAddress");
        auto get = [&](auto& fn, const char* name) {
            fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(lib, name));
            if (!fn) fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(a.getProcAddress(name));
            if (!fn) fail(SS_ERROR_GL, std::string("libEGL.so.1 has no ") + name);
        };
        get(a.initialize, "eglInitialize");
        get(a.bindApi, "eglBindAPI");
        get(a.chooseConfig, "eglChooseConfig");
        get(a.createContext, "eglCreateContext");
        get(a.destroyContext, "eglDestroyContext");
        get(a.makeCurrent, "eglMakeCurrent");
        get(a.releaseThread, "eglReleaseThread");
        get(a.getError, "eglGetError");
        get(a.queryString, "eglQueryString");
        get(a.getPlatformDisplay, "eglGetPlatformDisplayEXT");
        return a;
    }();
    return api;
}

std::string eglErrorText(const EglApi& egl) {
    char buf[16];
    snprintf(buf, sizeof buf, "0x%04x", unsigned(egl.getError()));
    return std::string("EGL error ") + buf;
}

class EglContext final : public Context {
public:
    EglContext() : egl_(eglApi()) {
        // The surfaceless platform needs no X server; it is the same display Blender's EEVEE
        // uses, which is why it is initialised (a no-op when already so) and never terminated.
        display_ = egl_.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display_ == EGL_NO_DISPLAY)
            fail(SS_ERROR_GL, "eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) gave no display");
        EGLint major = 0, minor = 0;
        if (!egl_.initialize(display_, &major, &minor))
            fail(SS_ERROR_GL, "eglInitialize failed on the surfaceless display (" + eglErrorText(egl_) + ")");
        if (!egl_.bindApi(EGL_OPENGL_API)) fail(SS_ERROR_GL, "eglBindAPI(EGL_OPENGL_API) failed");

        const char* ext = egl_.queryString(display_, EGL_EXTENSIONS);
        std::string extensions = ext ? ext : "";
        if (extensions.find("EGL_KHR_surfaceless_context") == std::string::npos)
            fail(SS_ERROR_GL, "the EGL display lacks EGL_KHR_surfaceless_context");
        EGLConfig config = nullptr;  // EGL_NO_CONFIG_KHR
        if (extensions.find("EGL_KHR_no_config_context") == std::string::npos) {
            const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint count = 0;
            if (!egl_.chooseConfig(display_, want, &config, 1, &count) || count < 1)
                fail(SS_ERROR_GL, "no EGL config renders OpenGL on the surfaceless display");
        }
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};
        context_ = egl_.createContext(display_, config, EGL_NO_CONTEXT, attribs);
        if (context_ == EGL_NO_CONTEXT)
            fail(SS_ERROR_GL, "eglCreateContext for OpenGL 4.5 core failed (" + eglErrorText(egl_) + ")");
    }

    ~EglContext() override {
        // Errors are ignored: at process exit Blender may already have terminated the display.
        egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        egl_.destroyContext(display_, context_);
        egl_.releaseThread();
    }

    const char* backendName() const override { return "egl"; }

    void makeCurrent() override {
        if (!egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            fail(SS_ERROR_GL, "eglMakeCurrent with no surface failed (" + eglErrorText(egl_) + ")");
    }

    void releaseCurrent() override {
        egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }

    void* getProcAddress(const char* name) const override {
        return reinterpret_cast<void*>(egl_.getProcAddress(name));
    }

private:
    const EglApi& egl_;
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<Context> createEglContext() { return std::make_unique<EglContext>(); }

}  // namespace ss::gl
