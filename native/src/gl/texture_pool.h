// Which texture storage a render thread keeps for reuse after its Textures are destroyed.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "gl/gl_functions.h"

namespace ss::gl {

// A released texture of exactly this size and format, or 0. llvmpipe allocates texture storage
// lazily, so every fresh render target pays page faults on its first draw (~10 ms per 1024²
// RGBA32F); each new SceneCache (a new scene: a farm frame's, a CLI run's) makes its camera pass and
// shadow maps afresh. The contents are stale: users clear what they read.
GLuint takePooledTexture(int width, int height, GLenum format);
// Keeps `id` (immutable storage width x height, `format`) for reuse; the oldest entries are
// deleted once the pool holds more than kMaxPooledBytes.
void poolTexture(GLuint id, int width, int height, GLenum format);
// Deletes the pooled textures of this thread (before its context dies).
void releaseThreadTexturePool();

constexpr size_t kMaxPooledBytes = size_t(256) << 20;

}  // namespace ss::gl
