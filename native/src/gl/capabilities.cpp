// How the context's limits are queried and float blending, float filtering and compute probed.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/capabilities.h"
#include "gl/context.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/render_state.h"

namespace ss::gl {

namespace {

std::string str(const Functions& gl, GLenum name) {
    const GLubyte* s = gl.GetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}

int integer(const Functions& gl, GLenum name) {
    GLint v = 0;
    gl.GetIntegerv(name, &v);
    return v;
}

// 1 + 2^-20 accumulated on top of 1.0 is exact only with true 32-bit float blending.
bool probeBlending() {
    Framebuffer fb(1, 1, {GL_RGBA32F});
    fb.bind();
    fb.clearColor(0, glm::vec4(1.0f));
    apply(states::additive);
    const Program& p = program("common/fullscreen.vert.glsl", "common/probe_constant.frag.glsl");
    p.use();
    const float step = std::ldexp(1.0f, -20);
    p.set("uValue", glm::vec4(step));
    GLuint vao = 0;
    api().CreateVertexArrays(1, &vao);
    VertexArrayHandle hold(vao);
    api().BindVertexArray(vao);
    api().DrawArrays(GL_TRIANGLES, 0, 3);
    api().DrawArrays(GL_TRIANGLES, 0, 3);
    api().BindVertexArray(0);
    apply(states::overwrite);
    float got = fb.readRgba(0)[0].x;
    return got == 1.0f + 2.0f * step;
}

// A compute shader samples halfway between texels 0 and 1 of an R32F texture (0 and 1).
void probeCompute(bool* compute, bool* filtering) {
    Texture tex(2, 1, GL_R32F, GL_LINEAR);
    const float texels[2] = {0.0f, 1.0f};
    api().TextureSubImage2D(tex.id(), 0, 0, 0, 2, 1, GL_RED, GL_FLOAT, texels);
    float init = -1.0f;
    BufferHandle out = makeBuffer(&init, sizeof init, true);
    ProgramDesc d;
    d.compute = "common/probe_filter.comp.glsl";
    const Program& p = program(d);
    p.use();
    p.setTexture("uTexture", 0, tex.id());
    api().BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out.id());
    api().DispatchCompute(1, 1, 1);
    api().MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    float got = -1.0f;
    api().GetNamedBufferSubData(out.id(), 0, sizeof got, &got);
    *compute = got >= 0.0f;
    *filtering = std::abs(got - 0.5f) < 1e-3f;
}

}  // namespace

Capabilities probeCapabilities() {
    const Functions& gl = api();
    Capabilities c;
    c.renderer = str(gl, GL_RENDERER);
    c.vendor = str(gl, GL_VENDOR);
    c.version = str(gl, GL_VERSION);
    c.glsl = str(gl, GL_SHADING_LANGUAGE_VERSION);
    c.maxTextureSize = integer(gl, GL_MAX_TEXTURE_SIZE);
    c.maxColorAttachments = integer(gl, GL_MAX_COLOR_ATTACHMENTS);
    c.maxDrawBuffers = integer(gl, GL_MAX_DRAW_BUFFERS);
    c.maxComputeInvocations = integer(gl, GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
    try {
        c.floatBlending = probeBlending();
    } catch (const std::exception&) {
        c.floatBlending = false;
    }
    try {
        probeCompute(&c.compute, &c.floatFiltering);
    } catch (const std::exception&) {
        c.compute = c.floatFiltering = false;
    }
    while (gl.GetError() != GL_NO_ERROR) {
    }
    return c;
}

std::string Capabilities::toJson(const std::string& backend, const std::string& device) const {
    nlohmann::json j;
    j["backend"] = backend;
    if (!device.empty()) j["device"] = device;
    nlohmann::json devices = nlohmann::json::array();
    for (const EglDevice& d : eglDevices()) devices.push_back(d.describe());
    j["egl_devices"] = devices;
    j["renderer"] = renderer;
    j["vendor"] = vendor;
    j["version"] = version;
    j["glsl_version"] = glsl;
    j["limits"] = {{"max_texture_size", maxTextureSize},
                   {"max_color_attachments", maxColorAttachments},
                   {"max_draw_buffers", maxDrawBuffers},
                   {"max_compute_invocations", maxComputeInvocations},
                   {"float_blending", floatBlending},
                   {"float_filtering", floatFiltering},
                   {"compute", compute}};
    return j.dump();
}

}  // namespace ss::gl
