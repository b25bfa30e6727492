// How a named render state is applied to the current context.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/render_state.h"

namespace ss::gl {

void apply(const RenderState& s) {
    const Functions& gl = api();
    if (s.depthTest) gl.Enable(GL_DEPTH_TEST);
    else gl.Disable(GL_DEPTH_TEST);
    gl.DepthFunc(s.depthFunc);
    gl.DepthMask(s.depthWrite ? GL_TRUE : GL_FALSE);
    auto channel = [&](int bit) { return s.colorWrite && (s.channels & (1u << bit)) ? GL_TRUE : GL_FALSE; };
    gl.ColorMask(channel(0), channel(1), channel(2), channel(3));
    if (s.depthClamp) gl.Enable(GL_DEPTH_CLAMP);
    else gl.Disable(GL_DEPTH_CLAMP);
    if (s.blend) {
        gl.Enable(GL_BLEND);
        gl.BlendEquation(s.blendEquation);
        gl.BlendFunc(s.blendSrc, s.blendDst);
    } else {
        gl.Disable(GL_BLEND);
    }
    if (s.cullFace == GL_NONE) {
        gl.Disable(GL_CULL_FACE);
    } else {
        gl.Enable(GL_CULL_FACE);
        gl.CullFace(s.cullFace);
    }
    gl.Disable(GL_STENCIL_TEST);
    gl.Disable(GL_SCISSOR_TEST);
}

}  // namespace ss::gl
