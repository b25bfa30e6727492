// Which render targets a method may keep between frames on its render thread (scratch targets).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <vector>

#include "gl/framebuffer.h"

namespace ss::gl {

// A framebuffer for `purpose` with this size and these formats, made on first use and handed
// back on later calls from the same render thread: llvmpipe allocates texture storage lazily, so
// a fresh 2048² RGBA32F target costs ~35 ms of page faults before the first pixel is drawn. The
// contents are whatever the last user left: clear what you read. One target per purpose and
// shape; a purpose asked for at a new shape drops its old target.
Framebuffer& scratchFramebuffer(const std::string& purpose, int width, int height,
                                const std::vector<GLenum>& colorFormats, GLenum depthFormat = 0);

// A 2D array texture (one level, NEAREST, CLAMP_TO_EDGE) for `purpose`, kept the same way: a
// compute pass's output that is rebuilt every frame.
GLuint scratchTextureArray(const std::string& purpose, int width, int height, int layers, GLenum format);

// Deletes this thread's scratch targets larger than `keepBytes` each: between renders, so a
// full-size target of a large render (auto leaves one per candidate) lives for one render only.
void trimThreadScratchTargets(size_t keepBytes);

// Deletes this thread's scratch targets (the render thread calls it before its context dies).
void releaseThreadScratchTargets();

}  // namespace ss::gl
