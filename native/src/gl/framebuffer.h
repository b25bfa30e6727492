// How float render targets (MRT + depth) are made, bound and read back into top-row-first images.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "gl/objects.h"

namespace ss::gl {

// A framebuffer object whose colour attachments are float textures it owns (or borrows).
// GL stores row 0 at the bottom; every read-back here flips, so row 0 of an Image is the top,
// which is exactly the camera contract when the framebuffer was drawn with the camera's
// projection at the camera's resolution.
class Framebuffer {
public:
    Framebuffer() = default;
    // Owns one texture per entry of colorFormats (none: attach borrowed textures afterwards) (attachment i = COLOR_ATTACHMENTi) and, when
    // depthFormat != 0 (e.g. GL_DEPTH_COMPONENT32F), a depth texture.
    Framebuffer(int width, int height, const std::vector<GLenum>& colorFormats,
                GLenum depthFormat = 0, GLenum filter = GL_NEAREST);

    // Attach a texture someone else owns (e.g. the shared camera depth, for depth-tested passes
    // at camera resolution). It must outlive this framebuffer's use.
    void attachColor(int index, GLuint texture);
    void attachDepth(GLuint texture);

    // Binds for drawing: all colour attachments as draw buffers, viewport = full size.
    void bind() const;
    // Clears colour attachment i to v (float clear, any format).
    void clearColor(int index, const glm::vec4& v) const;
    void clearDepth(float depth = 1.0f) const;

    int width() const { return width_; }
    int height() const { return height_; }
    GLuint id() const { return fbo_.id(); }
    const Texture& color(int index) const { return colors_.at(size_t(index)); }
    const Texture& depth() const { return depth_; }
    GLuint colorId(int index) const { return attached_.at(size_t(index)); }

    // All four channels of colour attachment i, top row first (missing channels read 0,0,0,1).
    std::vector<glm::vec4> readRgba(int index) const;
    // Rows firstRow..firstRow+rows-1 of colour attachment i in GL order (bottom row first), for
    // reading a large attachment a band at a time.
    std::vector<glm::vec4> readRgbaRows(int index, int firstRow, int rows) const;
    // Channels 0..count-1 (count 1..4) of colour attachment i from one read-back, top row first.
    std::vector<Image> readChannels(int index, int count) const;
    // The depth attachment's [0,1] window depth as an Image, top row first.
    Image readDepth() const;

private:
    void checkComplete() const;
    // The one glReadnPixels of this framebuffer: colour attachment `index` (depth when < 0) in
    // `format`, GL row order (bottom row first), into `out` of `bytes`; all rows, or `rows` from
    // `firstRow`.
    void readGlRows(int index, GLenum format, void* out, size_t bytes, int firstRow = 0, int rows = -1) const;
    int width_ = 0, height_ = 0;
    FramebufferHandle fbo_;
    std::vector<Texture> colors_;
    std::vector<GLuint> attached_;  // texture per colour attachment (owned or borrowed)
    Texture depth_;
};

}  // namespace ss::gl
