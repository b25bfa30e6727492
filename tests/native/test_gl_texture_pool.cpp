// Does a render thread hand a destroyed texture's storage to the next one of the same shape?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <utility>

#include <gtest/gtest.h>

#include "gl/objects.h"
#include "gl/render_thread.h"

namespace ss {
namespace {

// A destroyed texture's storage comes back for the next texture of the same size and format,
// with the previous owner's sampling state undone; another size gets storage of its own.
TEST(GlTexturePool, ReusesStorageOfTheSameShapeWithFreshState) {
    gl::RenderThread thread(SS_BACKEND_AUTO);
    thread.run([] {
        const gl::Functions& g = gl::api();
        GLuint first = 0;
        {
            gl::Texture t(64, 32, GL_DEPTH_COMPONENT32F);
            t.setCompare(true);
            first = t.id();
        }
        gl::Texture again(64, 32, GL_DEPTH_COMPONENT32F);
        EXPECT_EQ(again.id(), first);
        GLint mode = -1;
        g.GetTextureParameteriv(again.id(), GL_TEXTURE_COMPARE_MODE, &mode);
        EXPECT_EQ(mode, GL_NONE);
        gl::Texture other(64, 32, GL_R32F);  // same size, other format
        EXPECT_NE(other.id(), first);
        gl::Texture moved = std::move(again);
        EXPECT_EQ(moved.id(), first);
    });
}

}  // namespace
}  // namespace ss
