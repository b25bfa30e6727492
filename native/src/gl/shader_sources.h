// Where the GLSL files under shaders/ live once they are embedded into the library.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <vector>

namespace ss::gl {

struct ShaderSource {
    const char* path;  // relative to shaders/, e.g. "shadow_map/camera.frag.glsl"
    const char* text;
};

const std::vector<ShaderSource>& shaderSources();

}  // namespace ss::gl
