// Which depth/blend/cull state each kind of pass uses, kept as a named table (reviewed as data).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "gl/gl_functions.h"

namespace ss::gl {

struct RenderState {
    const char* name;
    bool depthTest;
    GLenum depthFunc;
    bool depthWrite;
    bool colorWrite;
    bool blend;
    GLenum blendEquation;  // GL_FUNC_ADD, GL_MIN, GL_MAX
    GLenum blendSrc, blendDst;
    GLenum cullFace;       // GL_BACK, GL_FRONT, or GL_NONE for two-sided
    unsigned channels = 0xF;  // with colorWrite: which of R, G, B, A (bits 0..3) are written
    bool depthClamp = false;  // clamp depth to the far plane instead of clipping there
};

namespace states {
//                                        name            dTest  func        dWrite colour blend  equation      src      dst      cull
inline constexpr RenderState overwrite    {"overwrite",    false, GL_ALWAYS, false, true,  false, GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE};  // full-screen passes
inline constexpr RenderState opaque       {"opaque",       true,  GL_LESS,   true,  true,  false, GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE};  // G-buffer, shadow map (two-sided: meshes may be open)
inline constexpr RenderState depthOnly    {"depth_only",   true,  GL_LESS,   true,  false, false, GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE};
inline constexpr RenderState additive     {"additive",     false, GL_ALWAYS, false, true,  true,  GL_FUNC_ADD, GL_ONE, GL_ONE,  GL_NONE};  // accumulation (exact in 32F)
inline constexpr RenderState additiveDepthTested{"additive_depth_tested", true, GL_LEQUAL, false, true, true, GL_FUNC_ADD, GL_ONE, GL_ONE, GL_NONE};
inline constexpr RenderState minimum      {"minimum",      false, GL_ALWAYS, false, true,  true,  GL_MIN,      GL_ONE, GL_ONE,  GL_NONE};
inline constexpr RenderState maximum      {"maximum",      false, GL_ALWAYS, false, true,  true,  GL_MAX,      GL_ONE, GL_ONE,  GL_NONE};
inline constexpr RenderState multiply     {"multiply",     false, GL_ALWAYS, false, true,  true,  GL_FUNC_ADD, GL_DST_COLOR, GL_ZERO, GL_NONE};
inline constexpr RenderState opaqueDepthClamped{"opaque_depth_clamped", true, GL_LESS, true, true, false, GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE, 0xF, true};
}  // namespace states

// Sets every field of `state` (never relies on what the previous pass left).
void apply(const RenderState& state);

}  // namespace ss::gl
