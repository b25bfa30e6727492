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

void Framebuffer::readGlRows(int index, GLenum format, void* out, size_t bytes) const {
    const Functions& gl = api();
    if (index >= 0) gl.NamedFramebufferReadBuffer(fbo_.id(), GL_COLOR_ATTACHMENT0 + index);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.id());
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadnPixels(0, 0, width_, height_, format, GL_FLOAT, GLsizei(bytes), out);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl.check(index >= 0 ? "reading back a colour attachment" : "reading back depth");
}

namespace {

// Channel `channel` of GL rows (bottom row first, `stride` floats a pixel) as a top-row-first Image.
Image flipRowsToImage(const float* glRows, int width, int height, int stride, int channel) {
    Image img(width, height);
    for (int y = 0; y < height; ++y) {
        const float* row = glRows + size_t(height - 1 - y) * width * stride;
        for (int x = 0; x < width; ++x) img.at(x, y) = row[size_t(x) * stride + channel];
    }
    return img;
}

}  // namespace

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

std::vector<Image> Framebuffer::readChannels(int index, int count) const {
    static const GLenum formats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    if (count < 1 || count > 4) fail(SS_ERROR_INTERNAL, "channel count must be 1..4");
    std::vector<float> rows(size_t(width_) * height_ * size_t(count));
    readGlRows(index, formats[count - 1], rows.data(), rows.size() * sizeof(float));
    std::vector<Image> out;
    for (int c = 0; c < count; ++c) out.push_back(flipRowsToImage(rows.data(), width_, height_, count, c));
    return out;
}

Image Framebuffer::readDepth() const {
    std::vector<float> rows(size_t(width_) * height_);
    readGlRows(-1, GL_DEPTH_COMPONENT, rows.data(), rows.size() * sizeof(float));
    return flipRowsToImage(rows.data(), width_, height_, 1, 0);
}

}  // namespace ss::gl
