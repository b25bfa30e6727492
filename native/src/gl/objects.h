// How GL objects (textures, buffers, vertex arrays) are owned: move-only, deleted on the render thread.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>

#include "gl/gl_functions.h"

namespace ss::gl {

// Deletion needs the context: a handle destroyed off the render thread (after shutdown, when the
// context and everything in it is already gone) just forgets its name.
template <void (*Delete)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint id) : id_(id) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = 0; }
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = o.id_;
            o.id_ = 0;
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    // Gives up the name without deleting it.
    GLuint release() {
        GLuint id = id_;
        id_ = 0;
        return id;
    }
    void reset() {
        if (id_ && current()) Delete(id_);
        id_ = 0;
    }

private:
    GLuint id_ = 0;
};

void deleteTexture(GLuint id);
void deleteBuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteFramebuffer(GLuint id);

using BufferHandle = Handle<deleteBuffer>;
using VertexArrayHandle = Handle<deleteVertexArray>;
using FramebufferHandle = Handle<deleteFramebuffer>;

// A 2D texture with immutable storage, clamped at the edges.
class Texture {
public:
    Texture() = default;
    // internalFormat: GL_RGBA32F, GL_RG32F, GL_R32F, GL_DEPTH_COMPONENT32F, GL_R32UI, ...
    // filter: GL_NEAREST or GL_LINEAR (32F linear filtering works on llvmpipe).
    // The storage may be a released texture's of the same size and format (gl/texture_pool.h):
    // its contents are undefined, as GL leaves new storage.
    Texture(int width, int height, GLenum internalFormat, GLenum filter = GL_NEAREST);
    ~Texture();
    Texture(Texture&&) noexcept = default;
    Texture& operator=(Texture&& o) noexcept;
    GLuint id() const { return handle_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }
    GLenum format() const { return format_; }
    explicit operator bool() const { return bool(handle_); }
    void setFilter(GLenum filter) const;
    // Enables hardware depth comparison (sampler2DShadow) on a depth texture.
    void setCompare(bool on, GLenum func = GL_LEQUAL) const;

private:
    Handle<deleteTexture> handle_;
    int width_ = 0, height_ = 0;
    GLenum format_ = 0;
};

// A buffer filled once (GL_STATIC_DRAW-like immutable storage unless dynamic).
BufferHandle makeBuffer(const void* data, size_t bytes, bool dynamic = false);

}  // namespace ss::gl
