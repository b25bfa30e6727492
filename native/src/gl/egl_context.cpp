// How an EGL 4.5 core context is made without a window: on a hardware EGL device when there is
// one (EGL_EXT_device_enumeration), else on Mesa's surfaceless platform (libEGL opened lazily).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <dlfcn.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "core/error.h"
#include "gl/context.h"

namespace ss::gl {

namespace {

// The EGL entry points we always need: (type, member, EGL name). One list makes both the
// members of EglApi and their look-ups.
#define SS_EGL_REQUIRED_FUNCTIONS(X)                                   \
    X(PFNEGLINITIALIZEPROC, initialize, eglInitialize)                 \
    X(PFNEGLBINDAPIPROC, bindApi, eglBindAPI)                          \
    X(PFNEGLCHOOSECONFIGPROC, chooseConfig, eglChooseConfig)           \
    X(PFNEGLCREATECONTEXTPROC, createContext, eglCreateContext)        \
    X(PFNEGLDESTROYCONTEXTPROC, destroyContext, eglDestroyContext)     \
    X(PFNEGLMAKECURRENTPROC, makeCurrent, eglMakeCurrent)              \
    X(PFNEGLRELEASETHREADPROC, releaseThread, eglReleaseThread)        \
    X(PFNEGLGETERRORPROC, getError, eglGetError)                       \
    X(PFNEGLQUERYSTRINGPROC, queryString, eglQueryString)              \
    X(PFNEGLGETPLATFORMDISPLAYEXTPROC, getPlatformDisplay, eglGetPlatformDisplayEXT)

// The EGL entry points we use, resolved from the dlopen'ed library: linking libEGL would make
// the whole library unloadable on a machine without it.
struct EglApi {
    PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
#define SS_EGL_MEMBER(type, member, name) type member = nullptr;
    SS_EGL_REQUIRED_FUNCTIONS(SS_EGL_MEMBER)
#undef SS_EGL_MEMBER
    // Optional (EGL_EXT_device_enumeration / EGL_EXT_device_query): null when absent.
    PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
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
#define SS_EGL_LOOKUP(type, member, name) get(a.member, #name);
        SS_EGL_REQUIRED_FUNCTIONS(SS_EGL_LOOKUP)
#undef SS_EGL_LOOKUP
#undef SS_EGL_REQUIRED_FUNCTIONS
        const char* client = a.queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        std::string clientExtensions = client ? client : "";
        if (clientExtensions.find("EGL_EXT_device_enumeration") != std::string::npos ||
            clientExtensions.find("EGL_EXT_device_base") != std::string::npos) {
            a.queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(a.getProcAddress("eglQueryDevicesEXT"));
            a.queryDeviceString =
                reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(a.getProcAddress("eglQueryDeviceStringEXT"));
        }
        return a;
    }();
    return api;
}

std::string eglErrorText(const EglApi& egl) {
    char buf[16];
    snprintf(buf, sizeof buf, "0x%04x", unsigned(egl.getError()));
    return std::string("EGL error ") + buf;
}

std::vector<EGLDeviceEXT> deviceHandles(const EglApi& egl) {
    if (!egl.queryDevices) return {};
    EGLint count = 0;
    if (!egl.queryDevices(0, nullptr, &count) || count <= 0) return {};
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count), EGLDeviceEXT{});
    if (!egl.queryDevices(count, devices.data(), &count)) return {};
    devices.resize(size_t(count));
    return devices;
}

EglDevice describeDevice(const EglApi& egl, EGLDeviceEXT handle, int index) {
    EglDevice d;
    d.index = index;
    if (egl.queryDeviceString) {
        const char* ext = egl.queryDeviceString(handle, EGL_EXTENSIONS);
        d.extensions = ext ? ext : "";
        if (d.extensions.find("EGL_EXT_device_drm") != std::string::npos) {
            const char* file = egl.queryDeviceString(handle, EGL_DRM_DEVICE_FILE_EXT);
            d.drmFile = file ? file : "";
        }
    }
    d.software = d.extensions.find("EGL_MESA_device_software") != std::string::npos;
    return d;
}

// Where the context goes: a device index, or -1 for the surfaceless platform.
struct Placement {
    std::vector<int> candidates;  // tried in order; -1 = surfaceless
    bool chosen = false;          // by SOFTSHADOW_EGL_DEVICE: no fallback
};

Placement placement(const EglApi& egl) {
    std::vector<EGLDeviceEXT> handles = deviceHandles(egl);
    const char* env = std::getenv(kEglDeviceVariable);
    std::string want = env ? env : "";
    Placement p;
    if (want == "surfaceless") {
        p.candidates = {-1};
        p.chosen = true;
        return p;
    }
    if (!want.empty() && want != "auto") {
        char* end = nullptr;
        long index = std::strtol(want.c_str(), &end, 10);
        if (*end != '\0' || index < 0 || size_t(index) >= handles.size())
            fail(SS_ERROR_GL, std::string(kEglDeviceVariable) + "='" + want +
                                  "' is neither 'auto', 'surfaceless' nor an EGL device index (this machine has " +
                                  std::to_string(handles.size()) + " EGL devices)");
        p.candidates = {int(index)};
        p.chosen = true;
        return p;
    }
    // A GPU first: llvmpipe is what surfaceless gives anyway.
    for (size_t i = 0; i < handles.size(); ++i)
        if (!describeDevice(egl, handles[i], int(i)).software) p.candidates.push_back(int(i));
    p.candidates.push_back(-1);
    return p;
}

class EglContext final : public Context {
public:
    EglContext() : egl_(eglApi()) {
        Placement p = placement(egl_);
        std::string errors;
        for (int candidate : p.candidates) {
            try {
                open(candidate);
                return;
            } catch (const Error& e) {
                if (p.chosen) throw;
                errors += std::string(errors.empty() ? "" : "; ") + e.what();
            }
        }
        fail(SS_ERROR_GL, "no EGL device made a context: " + errors);
    }

    ~EglContext() override {
        // Errors are ignored: at process exit Blender may already have terminated the display.
        egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        egl_.destroyContext(display_, context_);
        egl_.releaseThread();
    }

    const char* backendName() const override { return "egl"; }
    std::string device() const override { return device_; }

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
    // device -1: the surfaceless platform. It needs no X server; it is the same display
    // Blender's EEVEE uses, which is why it is initialised (a no-op when already so) and never
    // terminated; a device display is treated the same way.
    void open(int device) {
        std::string where;
        if (device < 0) {
            where = "the surfaceless display";
            display_ = egl_.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            if (display_ == EGL_NO_DISPLAY)
                fail(SS_ERROR_GL, "eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) gave no display");
            device_ = "surfaceless";
        } else {
            std::vector<EGLDeviceEXT> handles = deviceHandles(egl_);
            EglDevice d = describeDevice(egl_, handles.at(size_t(device)), device);
            where = "EGL " + d.describe();
            display_ = egl_.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, handles[size_t(device)], nullptr);
            if (display_ == EGL_NO_DISPLAY)
                fail(SS_ERROR_GL, "eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT) gave no display for " + where);
            device_ = d.describe();
        }
        EGLint major = 0, minor = 0;
        if (!egl_.initialize(display_, &major, &minor))
            fail(SS_ERROR_GL, "eglInitialize failed on " + where + " (" + eglErrorText(egl_) + ")");
        if (!egl_.bindApi(EGL_OPENGL_API)) fail(SS_ERROR_GL, "eglBindAPI(EGL_OPENGL_API) failed");

        const char* ext = egl_.queryString(display_, EGL_EXTENSIONS);
        std::string extensions = ext ? ext : "";
        if (extensions.find("EGL_KHR_surfaceless_context") == std::string::npos)
            fail(SS_ERROR_GL, where + " lacks EGL_KHR_surfaceless_context");
        EGLConfig config = nullptr;  // EGL_NO_CONFIG_KHR
        if (extensions.find("EGL_KHR_no_config_context") == std::string::npos) {
            const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint count = 0;
            if (!egl_.chooseConfig(display_, want, &config, 1, &count) || count < 1)
                fail(SS_ERROR_GL, "no EGL config renders OpenGL on " + where);
        }
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};
        context_ = egl_.createContext(display_, config, EGL_NO_CONTEXT, attribs);
        if (context_ == EGL_NO_CONTEXT)
            fail(SS_ERROR_GL, "eglCreateContext for OpenGL 4.5 core failed on " + where + " (" +
                                  eglErrorText(egl_) + ")");
    }

private:
    const EglApi& egl_;
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
    std::string device_;
};

}  // namespace

std::string EglDevice::describe() const {
    std::string s = "device " + std::to_string(index);
    if (!drmFile.empty()) s += " (" + drmFile + ")";
    if (software) s += " (software)";
    return s;
}

std::vector<EglDevice> eglDevices() {
    try {
        const EglApi& egl = eglApi();
        std::vector<EglDevice> out;
        std::vector<EGLDeviceEXT> handles = deviceHandles(egl);
        for (size_t i = 0; i < handles.size(); ++i) out.push_back(describeDevice(egl, handles[i], int(i)));
        return out;
    } catch (const Error&) {
        return {};  // no libEGL: no devices
    }
}

std::unique_ptr<Context> createEglContext() { return std::make_unique<EglContext>(); }

}  // namespace ss::gl
