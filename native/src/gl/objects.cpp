// How textures and buffers are created and deleted through the current function table.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/objects.h"

#include <string>

#include "core/error.h"
#include "gl/texture_pool.h"

namespace ss::gl {

void deleteTexture(GLuint id) { current()->DeleteTextures(1, &id); }
void deleteBuffer(GLuint id) { current()->DeleteBuffers(1, &id); }
void deleteVertexArray(GLuint id) { current()->DeleteVertexArrays(1, &id); }
void deleteFramebuffer(GLuint id) { current()->DeleteFramebuffers(1, &id); }

Texture::Texture(int width, int height, GLenum internalFormat, GLenum filter)
    : width_(width), height_(height), format_(internalFormat) {
    const Functions& gl = api();
    GLint maxSize = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (width <= 0 || height <= 0 || width > maxSize || height > maxSize)
        fail(SS_ERROR_GL, "texture size " + std::to_string(width) + "x" + std::to_string(height) +
                              " is outside 1.." + std::to_string(maxSize));
    GLuint id = takePooledTexture(width, height, internalFormat);
    if (id) {
        handle_ = Handle<deleteTexture>(id);
        setCompare(false);  // what a previous owner may have set; filter and wrap follow
    } else {
        gl.CreateTextures(GL_TEXTURE_2D, 1, &id);
        handle_ = Handle<deleteTexture>(id);
        gl.TextureStorage2D(id, 1, internalFormat, width, height);
    }
    gl.TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    setFilter(filter);
    gl.check("creating a texture");
}

Texture::~Texture() {
    if (handle_ && current()) poolTexture(handle_.release(), width_, height_, format_);
}

Texture& Texture::operator=(Texture&& o) noexcept {
    if (this != &o) {
        if (handle_ && current()) poolTexture(handle_.release(), width_, height_, format_);
        handle_ = std::move(o.handle_);
        width_ = o.width_, height_ = o.height_, format_ = o.format_;
    }
    return *this;
}

void Texture::setFilter(GLenum filter) const {
    const Functions& gl = api();
    gl.TextureParameteri(id(), GL_TEXTURE_MIN_FILTER, GLint(filter));
    gl.TextureParameteri(id(), GL_TEXTURE_MAG_FILTER, GLint(filter));
}

void Texture::setCompare(bool on, GLenum func) const {
    const Functions& gl = api();
    gl.TextureParameteri(id(), GL_TEXTURE_COMPARE_MODE, on ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
    gl.TextureParameteri(id(), GL_TEXTURE_COMPARE_FUNC, GLint(func));
}

BufferHandle makeBuffer(const void* data, size_t bytes, bool dynamic) {
    const Functions& gl = api();
    GLuint id = 0;
    gl.CreateBuffers(1, &id);
    BufferHandle h(id);
    // Zero-sized storage is an error in GL; an empty mesh still gets a valid (tiny) buffer.
    gl.NamedBufferStorage(id, GLsizeiptr(bytes ? bytes : 4), bytes ? data : nullptr,
                          dynamic ? GL_DYNAMIC_STORAGE_BIT : 0);
    gl.check("creating a buffer");
    return h;
}

}  // namespace ss::gl
