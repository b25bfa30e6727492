// Where GL work runs: one long-lived thread per context, so the host's thread never sees our GL.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <memory>
#include <string>

#include "softshadow/softshadow.h"

namespace ss::gl {

// A thread that creates a GL context, keeps it current for its whole life and runs jobs on it.
// Blender's rules (docs/gl.md): our context is never current on the caller's thread, the EGL
// display is never terminated, and the thread is joined before the process exits (stop(),
// ss::shutdownRenderThreads() and a static destructor all do it).
class RenderThread {
public:
    // Starts the thread and creates the context there: EGL, OSMesa, or auto (EGL then OSMesa).
    // Throws ss::Error(SS_ERROR_GL) naming every backend tried and why it failed.
    explicit RenderThread(ss_backend backend);
    ~RenderThread();
    RenderThread(const RenderThread&) = delete;
    RenderThread& operator=(const RenderThread&) = delete;

    // Runs `job` on the render thread with the context current and waits for it; an exception
    // thrown by the job is rethrown here. Called from the render thread itself, runs inline.
    // Throws ss::Error(SS_ERROR_GL) once the thread has been stopped.
    void run(const std::function<void()>& job);

    // Destroys the context (on its thread) and joins. Idempotent.
    void stop();
    bool running() const;

    const std::string& backendName() const { return backendName_; }
    const std::string& device() const { return device_; }  // Context::device()

private:
    struct State;
    std::shared_ptr<State> state_;
    std::string backendName_;
    std::string device_;
};

}  // namespace ss::gl

namespace ss {
// Joins every render thread still alive (the C API's ss_shutdown and a static destructor).
void shutdownRenderThreads();
}  // namespace ss
