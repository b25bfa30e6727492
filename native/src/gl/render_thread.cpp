// How the render thread owns its context, runs jobs one at a time and is joined at shutdown.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/render_thread.h"
#include "gl/scratch_targets.h"
#include "gl/texture_pool.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <set>
#include <thread>

#include "core/error.h"
#include "core/libstdcxx_baseline.h"
#include "gl/context.h"
#include "gl/gl_functions.h"
#include "gl/program.h"

namespace ss::gl {

const char* backendName(ss_backend backend) {
    switch (backend) {
        case SS_BACKEND_AUTO: return "auto";
        case SS_BACKEND_EGL: return "egl";
        case SS_BACKEND_OSMESA: return "osmesa";
        default: break;
    }
    fail(SS_ERROR_INVALID_ARGUMENT,
         "unknown GL backend " + std::to_string(int(backend)) + " (known: auto, egl, osmesa)");
}

struct RenderThread::State {
    std::mutex callers;  // one job at a time
    std::mutex m;
    std::condition_variable cv;
    const std::function<void()>* job = nullptr;
    std::exception_ptr jobError;
    bool jobDone = false;
    bool stopping = false;
    bool stopped = false;
    std::thread thread;
    std::thread::id threadId;
};

namespace {

// Every live render thread, so one call (or the static destructor below) joins them all.
// Allocated once and never freed: a RenderThread destroyed during static destruction (a host's
// global context) must still find it.
struct Registry {
    std::mutex m;
    std::set<RenderThread*> threads;
    void stopAll() {
        std::lock_guard lock(m);
        for (RenderThread* t : threads) t->stop();
    }
};
Registry& registry() {
    static Registry* r = new Registry;
    return *r;
}

// Joins every render thread when the library is unloaded or the process exits, so no thread
// outlives the code it runs (Blender crashed at exit when one did).
struct JoinAtExit {
    ~JoinAtExit() { registry().stopAll(); }
} joinAtExit;

std::unique_ptr<Context> createContext(ss_backend backend) {
    std::string why;
    auto attempt = [&](const char* name, std::unique_ptr<Context> (*make)()) -> std::unique_ptr<Context> {
        try {
            auto ctx = make();
            ctx->makeCurrent();
            return ctx;
        } catch (const std::exception& e) {
            why += std::string(why.empty() ? "" : "; ") + name + ": " + e.what();
            return nullptr;
        }
    };
    std::unique_ptr<Context> ctx;
    if (backend == SS_BACKEND_EGL || backend == SS_BACKEND_AUTO) ctx = attempt("egl", createEglContext);
    if (!ctx && (backend == SS_BACKEND_OSMESA || backend == SS_BACKEND_AUTO))
        ctx = attempt("osmesa", createOsmesaContext);
    if (!ctx) fail(SS_ERROR_GL, "no GL backend could make a context (" + why + ")");
    return ctx;
}

}  // namespace

RenderThread::RenderThread(ss_backend backend) : state_(std::make_shared<State>()) {
    gl::backendName(backend);  // rejects unknown values before a thread exists
    std::exception_ptr startError;
    bool started = false;
    auto s = state_;
    std::string name, device;
    s->thread = std::thread([s, backend, &startError, &started, &name, &device] {
        std::unique_ptr<Context> ctx;
        Functions fn;
        {
            std::unique_lock lock(s->m);
            try {
                ctx = createContext(backend);
                fn.load([&](const char* n) { return ctx->getProcAddress(n); });
                setCurrent(&fn);
                name = ctx->backendName();
                device = ctx->device();
            } catch (...) {
                startError = std::current_exception();
                ctx.reset();
            }
            started = true;
            s->cv.notify_all();
            if (!ctx) {
                s->stopped = true;
                return;
            }
        }
        for (;;) {
            std::unique_lock lock(s->m);
            s->cv.wait(lock, [&] { return s->job || s->stopping; });
            if (s->stopping) break;
            const std::function<void()>* job = s->job;
            lock.unlock();
            std::exception_ptr error;
            try {
                (*job)();
            } catch (...) {
                error = std::current_exception();
            }
            lock.lock();
            s->job = nullptr;
            s->jobError = error;
            s->jobDone = true;
            s->cv.notify_all();
        }
        releaseThreadScratchTargets();
        releaseThreadPrograms();
        releaseThreadTexturePool();  // last: the targets above return their textures to it
        setCurrent(nullptr);
        ctx->releaseCurrent();
        ctx.reset();
    });
    s->threadId = s->thread.get_id();
    {
        std::unique_lock lock(s->m);
        s->cv.wait(lock, [&] { return started; });
    }
    if (startError) {
        s->thread.join();
        std::rethrow_exception(startError);
    }
    backendName_ = name;
    device_ = device;
    std::lock_guard lock(registry().m);
    registry().threads.insert(this);
}

RenderThread::~RenderThread() {
    {
        std::lock_guard lock(registry().m);
        registry().threads.erase(this);
    }
    stop();
}

void RenderThread::run(const std::function<void()>& job) {
    if (std::this_thread::get_id() == state_->threadId) {
        job();
        return;
    }
    std::lock_guard caller(state_->callers);
    std::unique_lock lock(state_->m);
    if (state_->stopping || state_->stopped)
        fail(SS_ERROR_GL, "the GL render thread has been shut down (ss_shutdown was called)");
    state_->job = &job;
    state_->jobDone = false;
    state_->jobError = nullptr;
    state_->cv.notify_all();
    state_->cv.wait(lock, [&] { return state_->jobDone; });
    if (state_->jobError) std::rethrow_exception(state_->jobError);
}

void RenderThread::stop() {
    std::lock_guard caller(state_->callers);  // waits for a running job to finish
    {
        std::lock_guard lock(state_->m);
        if (state_->stopped) return;
        state_->stopping = true;
        state_->cv.notify_all();
    }
    if (state_->thread.joinable()) state_->thread.join();
    std::lock_guard lock(state_->m);
    state_->stopped = true;
}

bool RenderThread::running() const {
    std::lock_guard lock(state_->m);
    return !state_->stopped && !state_->stopping;
}

}  // namespace ss::gl

namespace ss {
void shutdownRenderThreads() { gl::registry().stopAll(); }
}  // namespace ss
