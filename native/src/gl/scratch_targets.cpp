// How scratch render targets are kept per render thread (scratch_targets.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/scratch_targets.h"

#include <map>
#include <memory>

namespace ss::gl {

namespace {

struct Scratch {
    int width = 0, height = 0;
    std::vector<GLenum> colors;
    GLenum depth = 0;
    std::unique_ptr<Framebuffer> target;
};

// Per render thread: GL objects belong to that thread's context.
thread_local std::map<std::string, Scratch>* tScratch = nullptr;

}  // namespace

Framebuffer& scratchFramebuffer(const std::string& purpose, int width, int height,
                                const std::vector<GLenum>& colorFormats, GLenum depthFormat) {
    if (!tScratch) tScratch = new std::map<std::string, Scratch>();
    Scratch& s = (*tScratch)[purpose];
    if (!s.target || s.width != width || s.height != height || s.colors != colorFormats || s.depth != depthFormat) {
        s.target.reset();  // the old storage goes before the new is made
        s.target = std::make_unique<Framebuffer>(width, height, colorFormats, depthFormat);
        s.width = width, s.height = height, s.colors = colorFormats, s.depth = depthFormat;
    }
    return *s.target;
}

void releaseThreadScratchTargets() {
    delete tScratch;
    tScratch = nullptr;
}

}  // namespace ss::gl
