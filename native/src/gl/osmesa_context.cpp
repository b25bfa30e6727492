// How an OSMesa 4.5 core context is made (libOSMesa opened lazily with dlopen).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <dlfcn.h>

#include <GL/osmesa.h>

#include <string>
#include <vector>

#include "core/error.h"
#include "gl/context.h"

namespace ss::gl {

namespace {

struct OsmesaApi {
    OSMesaContext (*createContextAttribs)(const int*, OSMesaContext) = nullptr;
    void (*destroyContext)(OSMesaContext) = nullptr;
    GLboolean (*makeCurrent)(OSMesaContext, void*, GLenum, GLsizei, GLsizei) = nullptr;
    OSMESAproc (*getProcAddress)(const char*) = nullptr;
};

const OsmesaApi& osmesaApi() {
    static const OsmesaApi api = [] {
        OsmesaApi a;
        void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
        if (!lib) fail(SS_ERROR_GL, std::string("libOSMesa.so.8 could not be opened: ") + dlerror());
        auto get = [&](auto& fn, const char* name) {
            fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(lib, name));
            if (!fn) fail(SS_ERROR_GL, std::string("libOSMesa.so.8 has no ") + name);
        };
        get(a.createContextAttribs, "OSMesaCreateContextAttribs");
        get(a.destroyContext, "OSMesaDestroyContext");
        get(a.makeCurrent, "OSMesaMakeCurrent");
        get(a.getProcAddress, "OSMesaGetProcAddress");
        return a;
    }();
    return api;
}

class OsmesaContext final : public Context {
public:
    OsmesaContext() : api_(osmesaApi()) {
        const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                               OSMESA_DEPTH_BITS, 0,
                               OSMESA_STENCIL_BITS, 0,
                               OSMESA_ACCUM_BITS, 0,
                               OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION, 4,
                               OSMESA_CONTEXT_MINOR_VERSION, 5,
                               0};
        context_ = api_.createContextAttribs(attribs, nullptr);
        if (!context_) fail(SS_ERROR_GL, "OSMesaCreateContextAttribs for OpenGL 4.5 core failed");
    }

    ~OsmesaContext() override { api_.destroyContext(context_); }

    const char* backendName() const override { return "osmesa"; }

    void makeCurrent() override {
        // OSMesa cannot be current without a buffer; we render only into framebuffer objects,
        // so a tiny one does.
        if (!api_.makeCurrent(context_, dummy_.data(), GL_UNSIGNED_BYTE, kDummySize, kDummySize))
            fail(SS_ERROR_GL, "OSMesaMakeCurrent failed");
    }

    void releaseCurrent() override { api_.makeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0); }

    void* getProcAddress(const char* name) const override {
        return reinterpret_cast<void*>(api_.getProcAddress(name));
    }

private:
    static constexpr int kDummySize = 4;
    const OsmesaApi& api_;
    OSMesaContext context_ = nullptr;
    std::vector<unsigned char> dummy_ = std::vector<unsigned char>(kDummySize * kDummySize * 4);
};

}  // namespace

std::unique_ptr<Context> createOsmesaContext() { return std::make_unique<OsmesaContext>(); }

}  // namespace ss::gl
