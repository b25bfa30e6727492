// Does each GL backend make a context on the render thread that renders and reads back correctly?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <dlfcn.h>

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/render_state.h"
#include "gl/render_thread.h"
#include "renderer/renderer.h"

namespace ss {
namespace {

// A backend is skipped only when its library is truly not installed.
bool libraryPresent(const char* soname) {
    void* h = dlopen(soname, RTLD_NOW | RTLD_LOCAL);
    if (h) dlclose(h);
    return h != nullptr;
}

const char* libraryOf(ss_backend b) { return b == SS_BACKEND_EGL ? "libEGL.so.1" : "libOSMesa.so.8"; }

// Draws the window coordinates of every pixel of a 5x3 target and reads them back.
std::vector<glm::vec4> drawPattern(float tag) {
    gl::Framebuffer fb(5, 3, {GL_RGBA32F});
    fb.bind();
    fb.clearColor(0, glm::vec4(-1.0f));
    gl::apply(gl::states::overwrite);
    const gl::Program& p = gl::program("common/fullscreen.vert.glsl", "common/pattern.frag.glsl");
    p.use();
    p.set("uTag", tag);
    GLuint vao = 0;
    gl::api().CreateVertexArrays(1, &vao);
    gl::VertexArrayHandle hold(vao);
    gl::api().BindVertexArray(vao);
    gl::api().DrawArrays(GL_TRIANGLES, 0, 3);
    gl::api().BindVertexArray(0);
    gl::api().check("drawing the pattern");
    return fb.readRgba(0);
}

class GlBackend : public ::testing::TestWithParam<ss_backend> {};

TEST_P(GlBackend, RendersAndReadsBackTopRowFirst) {
    ss_backend backend = GetParam();
    if (!libraryPresent(libraryOf(backend)))
        GTEST_SKIP() << libraryOf(backend) << " is not installed: this backend cannot be tested";
    gl::RenderThread thread(backend);
    EXPECT_EQ(thread.backendName(), backend == SS_BACKEND_EGL ? "egl" : "osmesa");
    std::vector<glm::vec4> px;
    thread.run([&] { px = drawPattern(7.0f); });
    ASSERT_EQ(px.size(), 15u);
    // Row 0 of the read-back is the top: GL window row 2 of 3. Pixel centres sit at +0.5.
    // Exact equality: these small coordinates are exactly representable and interpolated exactly.
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) {
            const glm::vec4& v = px[size_t(y) * 5 + x];
            EXPECT_EQ(v.x, x + 0.5f) << "pixel " << x << "," << y;
            EXPECT_EQ(v.y, (2 - y) + 0.5f) << "pixel " << x << "," << y;
            EXPECT_EQ(v.z, 7.0f);
        }
}

TEST_P(GlBackend, CallerThreadNeverHasOurContextCurrent) {
    ss_backend backend = GetParam();
    if (!libraryPresent(libraryOf(backend)))
        GTEST_SKIP() << libraryOf(backend) << " is not installed: this backend cannot be tested";
    gl::RenderThread thread(backend);
    bool currentThere = false;
    thread.run([&] { currentThere = gl::current() != nullptr; });
    EXPECT_TRUE(currentThere);
    EXPECT_EQ(gl::current(), nullptr);
    EXPECT_THROW(gl::api(), Error);
    // Ask the backend's own library which context this thread has current.
    void* lib = dlopen(libraryOf(backend), RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(lib, nullptr);
    using GetCurrent = void* (*)();
    auto getCurrent = reinterpret_cast<GetCurrent>(
        dlsym(lib, backend == SS_BACKEND_EGL ? "eglGetCurrentContext" : "OSMesaGetCurrentContext"));
    ASSERT_NE(getCurrent, nullptr);
    EXPECT_EQ(getCurrent(), nullptr);
    dlclose(lib);
}

INSTANTIATE_TEST_SUITE_P(Backends, GlBackend, ::testing::Values(SS_BACKEND_EGL, SS_BACKEND_OSMESA),
                         [](const auto& info) { return info.param == SS_BACKEND_EGL ? "egl" : "osmesa"; });

TEST(GlRenderThread, RethrowsTheJobsErrorAndKeepsWorking) {
    gl::RenderThread thread(SS_BACKEND_AUTO);
    try {
        thread.run([] { throw Error(SS_ERROR_IO, "from the job"); });
        FAIL() << "the job's exception was swallowed";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_IO);
        EXPECT_STREQ(e.what(), "from the job");
    }
    std::vector<glm::vec4> px;
    thread.run([&] { px = drawPattern(3.0f); });
    EXPECT_EQ(px.at(0).z, 3.0f);
}

TEST(GlRenderThread, StopsOnShutdownAndRefusesWork) {
    gl::RenderThread thread(SS_BACKEND_AUTO);
    EXPECT_TRUE(thread.running());
    shutdownRenderThreads();
    EXPECT_FALSE(thread.running());
    try {
        thread.run([] {});
        FAIL() << "a stopped render thread ran a job";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_GL);
    }
}

TEST(GlRenderThread, UnknownBackendIsAnInvalidArgument) {
    try {
        gl::RenderThread thread(static_cast<ss_backend>(42));
        FAIL() << "backend 42 was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(e.what()).find("42"), std::string::npos) << e.what();
    }
    EXPECT_THROW(Renderer(static_cast<ss_backend>(-1)), Error);
}

TEST(GlProgram, ExpandsIncludesOnceAndPlacesDefinesAfterVersion) {
    std::string text = gl::expandShader("shadow_map/distance.frag.glsl", {"FOO", "BAR=3"});
    EXPECT_EQ(text.rfind("#version 450 core\n#define FOO\n#define BAR 3\n", 0), 0u) << text;
    size_t first = text.find("float shadowDistanceOf");
    ASSERT_NE(first, std::string::npos);
    EXPECT_EQ(text.find("float shadowDistanceOf", first + 1), std::string::npos);
    try {
        gl::expandShader("no_such/file.glsl", {});
        FAIL() << "a missing shader file was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no_such/file.glsl"), std::string::npos);
    }
}

TEST(GlProgram, CompileErrorsCarryTheInfoLogAndTheFileNames) {
    gl::RenderThread thread(SS_BACKEND_AUTO);
    std::string message;
    ss_status status = SS_OK;
    thread.run([&] {
        try {
            // A define that turns a valid file into an invalid one: vec4 becomes an unknown type.
            gl::program("common/fullscreen.vert.glsl", "common/probe_constant.frag.glsl",
                        {"vec4=noSuchType"});
        } catch (const Error& e) {
            status = e.status();
            message = e.what();
        }
    });
    EXPECT_EQ(status, SS_ERROR_GL);
    // The vertex stage compiles first and fails first (it uses vec4 too); the legend maps the
    // log's source numbers back to files.
    EXPECT_NE(message.find("shader 'common/fullscreen.vert.glsl'"), std::string::npos) << message;
    EXPECT_NE(message.find("= common/fullscreen.vert.glsl"), std::string::npos) << message;
    // Mesa's info log ("0:4(9): error: ...") follows our own sentence, which has no "error".
    EXPECT_NE(message.find("does not compile"), std::string::npos) << message;
    EXPECT_NE(message.find("error"), std::string::npos) << message;
}

TEST(GlRenderer, InfoReportsBackendAndProbedLimits) {
    Renderer renderer(SS_BACKEND_AUTO);
    nlohmann::json j = nlohmann::json::parse(renderer.info());
    EXPECT_TRUE(j["backend"] == "egl" || j["backend"] == "osmesa") << j.dump();
    EXPECT_FALSE(j["renderer"].get<std::string>().empty());
    EXPECT_NE(j["version"].get<std::string>().find("4.5"), std::string::npos) << j.dump();
    // docs/contracts.md "GL": every method relies on these.
    EXPECT_GE(j["limits"]["max_color_attachments"].get<int>(), 8);
    EXPECT_GE(j["limits"]["max_texture_size"].get<int>(), 4096);
    EXPECT_TRUE(j["limits"]["float_blending"].get<bool>());
    EXPECT_TRUE(j["limits"]["float_filtering"].get<bool>());
    EXPECT_TRUE(j["limits"]["compute"].get<bool>());
}

}  // namespace
}  // namespace ss
