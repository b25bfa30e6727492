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
    GLboolean c = s.colorWrite ? GL_TRUE : GL_FALSE;
    gl.ColorMask(c, c, c, c);
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
