// How released textures are kept per render thread and handed out again (texture_pool.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/texture_pool.h"

#include <deque>

#include "gl/gl_functions.h"

namespace ss::gl {

namespace {

struct Pooled {
    GLuint id;
    int width, height;
    GLenum format;
    size_t bytes;
};

struct Pool {
    std::deque<Pooled> entries;  // oldest first
    size_t bytes = 0;
};

thread_local Pool* tPool = nullptr;

size_t bytesPerTexel(GLenum format) {
    switch (format) {
        case GL_RGBA32F: return 16;
        case GL_RG32F:
        case GL_RGBA16F: return 8;
        case GL_R32F:
        case GL_R32UI:
        case GL_DEPTH_COMPONENT32F:
        case GL_RGBA8: return 4;
        default: return 16;  // an overestimate only makes the pool smaller
    }
}

void deleteName(GLuint id) {
    if (current()) current()->DeleteTextures(1, &id);
}

}  // namespace

GLuint takePooledTexture(int width, int height, GLenum format) {
    if (!tPool) return 0;
    for (auto it = tPool->entries.begin(); it != tPool->entries.end(); ++it)
        if (it->width == width && it->height == height && it->format == format) {
            GLuint id = it->id;
            tPool->bytes -= it->bytes;
            tPool->entries.erase(it);
            return id;
        }
    return 0;
}

void poolTexture(GLuint id, int width, int height, GLenum format) {
    if (!id) return;
    size_t bytes = size_t(width) * size_t(height) * bytesPerTexel(format);
    if (bytes > kMaxPooledBytes) {
        deleteName(id);
        return;
    }
    if (!tPool) tPool = new Pool();
    tPool->entries.push_back({id, width, height, format, bytes});
    tPool->bytes += bytes;
    while (tPool->bytes > kMaxPooledBytes) {
        tPool->bytes -= tPool->entries.front().bytes;
        deleteName(tPool->entries.front().id);
        tPool->entries.pop_front();
    }
}

void releaseThreadTexturePool() {
    if (!tPool) return;
    for (const Pooled& p : tPool->entries) deleteName(p.id);
    delete tPool;
    tPool = nullptr;
}

}  // namespace ss::gl
