// What "a GL context" is to the library, whichever backend made it (EGL or OSMesa).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <memory>
#include <string>
#include <vector>

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
    // Which device renders, for `info` ("surfaceless", "device 0 (/dev/dri/renderD128)"...);
    // empty where the backend has no choice of device.
    virtual std::string device() const { return ""; }
};

// One EGL device as EGL_EXT_device_enumeration lists it.
struct EglDevice {
    int index = 0;
    std::string drmFile;     // EGL_DRM_DEVICE_FILE_EXT, empty when the device has none
    std::string extensions;  // the device's own extension string
    bool software = false;   // EGL_MESA_device_software (llvmpipe)
    std::string describe() const;
};

// The EGL devices of this machine; empty when libEGL or the extension is missing. The EGL
// context renders on the first hardware device that makes a 4.5 core context, else on Mesa's
// surfaceless platform; SOFTSHADOW_EGL_DEVICE chooses instead: "surfaceless", or a device index.
std::vector<EglDevice> eglDevices();
constexpr const char* kEglDeviceVariable = "SOFTSHADOW_EGL_DEVICE";

// Each throws ss::Error(SS_ERROR_GL) saying why the backend is unusable (library missing,
// no display, no 4.5 core context...). Defined in egl_context.cpp / osmesa_context.cpp, the only
// files that include EGL or OSMesa headers.
std::unique_ptr<Context> createEglContext();
std::unique_ptr<Context> createOsmesaContext();

// "egl", "osmesa", "auto"; throws ss::Error(SS_ERROR_INVALID_ARGUMENT) for another value.
const char* backendName(ss_backend backend);

}  // namespace ss::gl
