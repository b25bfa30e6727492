// How float render targets are attached, checked, cleared and read back (rows flipped to top-first).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/framebuffer.h"

#include <algorithm>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"

namespace ss::gl {

Framebuffer::Framebuffer(int width, int height, const std::vector<GLenum>& colorFormats,
                         GLenum depthFormat, GLenum filter)
    : width_(width), height_(height) {
    const Functions& gl = api();
    GLuint id = 0;
    gl.CreateFramebuffers(1, &id);
    fbo_ = FramebufferHandle(id);
    for (size_t i = 0; i < colorFormats.size(); ++i) {
        colors_.emplace_back(width, height, colorFormats[i], filter);
        attachColor(int(i), colors_.back().id());
    }
    if (depthFormat) {
        depth_ = Texture(width, height, depthFormat, GL_NEAREST);
        attachDepth(depth_.id());
    }
}

void Framebuffer::attachColor(int index, GLuint texture) {
    const Functions& gl = api();
    gl.NamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0 + index, texture, 0);
    if (attached_.size() <= size_t(index)) attached_.resize(size_t(index) + 1, 0);
    attached_[size_t(index)] = texture;
    std::vector<GLenum> buffers;
    for (size_t i = 0; i < attached_.size(); ++i)
        buffers.push_back(attached_[i] ? GLenum(GL_COLOR_ATTACHMENT0 + i) : GLenum(GL_NONE));
    gl.NamedFramebufferDrawBuffers(fbo_.id(), GLsizei(buffers.size()), buffers.data());
}

void Framebuffer::attachDepth(GLuint texture) {
    api().NamedFramebufferTexture(fbo_.id(), GL_DEPTH_ATTACHMENT, texture, 0);
}

void Framebuffer::checkComplete() const {
    const Functions& gl = api();
    GLenum status = gl.CheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char buf[16];
        snprintf(buf, sizeof buf, "0x%04x", unsigned(status));
        fail(SS_ERROR_GL, std::string("framebuffer is incomplete (status ") + buf + ")");
    }
}

void Framebuffer::bind() const {
    const Functions& gl = api();
    if (attached_.empty()) gl.NamedFramebufferDrawBuffer(fbo_.id(), GL_NONE);
    checkComplete();
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    gl.Viewport(0, 0, width_, height_);
}

void Framebuffer::clearColor(int index, const glm::vec4& v) const {
    api().ClearNamedFramebufferfv(fbo_.id(), GL_COLOR, index, glm::value_ptr(v));
}

void Framebuffer::clearDepth(float depth) const {
    // Depth writes must be on for the clear to happen.
    const Functions& gl = api();
    gl.DepthMask(GL_TRUE);
    gl.ClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &depth);
}

void Framebuffer::readGlRows(int index, GLenum format, void* out, size_t bytes, int firstRow, int rows) const {
    const Functions& gl = api();
    if (index >= 0) gl.NamedFramebufferReadBuffer(fbo_.id(), GL_COLOR_ATTACHMENT0 + index);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.id());
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadnPixels(0, firstRow, width_, rows < 0 ? height_ : rows, format, GL_FLOAT, GLsizei(bytes), out);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl.check(index >= 0 ? "reading back a colour attachment" : "reading back depth");
}


std::vector<glm::vec4> Framebuffer::readRgba(int index) const {
    std::vector<glm::vec4> rows(size_t(width_) * height_);
    readGlRows(index, GL_RGBA, rows.data(), rows.size() * sizeof(glm::vec4));
    // Flipped in place: a second 16 MB vector at 1024² costs more in page faults than the swap.
    const size_t w = size_t(width_);
    for (int y = 0; y < height_ / 2; ++y)
        std::swap_ranges(rows.begin() + ptrdiff_t(size_t(y) * w), rows.begin() + ptrdiff_t(size_t(y) * w + w),
                         rows.begin() + ptrdiff_t(size_t(height_ - 1 - y) * w));
    return rows;
}

std::vector<glm::vec4> Framebuffer::readRgbaRows(int index, int firstRow, int rows) const {
    if (firstRow < 0 || rows < 0 || firstRow + rows > height_) fail(SS_ERROR_INTERNAL, "rows outside the framebuffer");
    std::vector<glm::vec4> out(size_t(width_) * size_t(rows));
    readGlRows(index, GL_RGBA, out.data(), out.size() * sizeof(glm::vec4), firstRow, rows);
    return out;
}

namespace {

// GL rows (bottom row first) in place to top-row-first.
void flipRows(Image& img) {
    const size_t w = size_t(img.width);
    for (int y = 0; y < img.height / 2; ++y)
        std::swap_ranges(img.pixels.begin() + ptrdiff_t(size_t(y) * w), img.pixels.begin() + ptrdiff_t(size_t(y) * w + w),
                         img.pixels.begin() + ptrdiff_t(size_t(img.height - 1 - y) * w));
}

}  // namespace

std::vector<Image> Framebuffer::readChannels(int index, int count) const {
    static const GLenum formats[] = {GL_RED, GL_GREEN, GL_BLUE};
    if (count < 1 || count > 4) fail(SS_ERROR_INTERNAL, "channel count must be 1..4");
    // One read-back per channel straight into its image, so the layers are the only full copy
    // held; alpha, which a core context cannot read alone, comes from RGBA bands of ~16 MiB.
    std::vector<Image> out;
    for (int c = 0; c < count; ++c) {
        Image img(width_, height_);
        if (c < 3) {
            readGlRows(index, formats[c], img.pixels.data(), img.pixels.size() * sizeof(float));
        } else {
            const int band = std::max(1, int((size_t(16) << 20) / (sizeof(glm::vec4) * size_t(width_))));
            for (int y = 0; y < height_; y += band) {
                const std::vector<glm::vec4> rows = readRgbaRows(index, y, std::min(band, height_ - y));
                for (size_t i = 0; i < rows.size(); ++i) img.pixels[size_t(y) * size_t(width_) + i] = rows[i].w;
            }
        }
        flipRows(img);
        out.push_back(std::move(img));
    }
    return out;
}

Image Framebuffer::readDepth() const {
    Image img(width_, height_);
    readGlRows(-1, GL_DEPTH_COMPONENT, img.pixels.data(), img.pixels.size() * sizeof(float));
    flipRows(img);
    return img;
}

}  // namespace ss::gl
