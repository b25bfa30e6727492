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

struct ScratchArray {
    int width = 0, height = 0, layers = 0;
    GLenum format = 0;
    Handle<deleteTexture> texture;
};

// Per render thread: GL objects belong to that thread's context.
thread_local std::map<std::string, Scratch>* tScratch = nullptr;
thread_local std::map<std::string, ScratchArray>* tArrays = nullptr;

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

GLuint scratchTextureArray(const std::string& purpose, int width, int height, int layers, GLenum format) {
    if (!tArrays) tArrays = new std::map<std::string, ScratchArray>();
    ScratchArray& a = (*tArrays)[purpose];
    if (!a.texture || a.width != width || a.height != height || a.layers != layers || a.format != format) {
        a.texture = Handle<deleteTexture>();
        const Functions& gl = api();
        GLuint id = 0;
        gl.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
        a.texture = Handle<deleteTexture>(id);
        gl.TextureStorage3D(id, 1, format, width, height, layers);
        gl.TextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl.TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl.check("creating a scratch texture array");
        a.width = width, a.height = height, a.layers = layers, a.format = format;
    }
    return a.texture.id();
}

namespace {

size_t texelBytes(GLenum format) {
    switch (format) {
        case GL_R32F: case GL_R32UI: case GL_R32I: case GL_RGBA8: case GL_DEPTH_COMPONENT32F: case GL_DEPTH_COMPONENT24:
            return 4;
        case GL_RG32F: case GL_RGBA16F: return 8;
        default: return 16;
    }
}

}  // namespace

void trimThreadScratchTargets(size_t keepBytes) {
    if (tScratch)
        for (auto it = tScratch->begin(); it != tScratch->end();) {
            size_t texel = it->second.depth ? texelBytes(it->second.depth) : 0;
            for (GLenum c : it->second.colors) texel += texelBytes(c);
            if (size_t(it->second.width) * size_t(it->second.height) * texel > keepBytes) it = tScratch->erase(it);
            else ++it;
        }
    if (tArrays)
        for (auto it = tArrays->begin(); it != tArrays->end();) {
            const ScratchArray& a = it->second;
            if (size_t(a.width) * size_t(a.height) * size_t(a.layers) * texelBytes(a.format) > keepBytes) it = tArrays->erase(it);
            else ++it;
        }
}

void releaseThreadScratchTargets() {
    delete tScratch;
    tScratch = nullptr;
    delete tArrays;
    tArrays = nullptr;
}

}  // namespace ss::gl
