// How a see-through mesh's UVs, material indices and alpha textures are uploaded.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/see_through.h"

#include "gl/gl_functions.h"

namespace ss {

GpuSeeThrough uploadSeeThrough(const MeshAlpha& alpha, size_t triangleCount) {
    const gl::Functions& g = gl::api();
    GpuSeeThrough out;
    out.cameraSeesThrough = alpha.cameraSeesThrough();
    std::vector<glm::vec2> uvs = alpha.cornerUvs;
    uvs.resize(3 * triangleCount, glm::vec2(0.0f));
    std::vector<uint32_t> materials = alpha.triangleMaterial;
    materials.resize(triangleCount, 0u);
    out.cornerUvs = gl::makeBuffer(uvs.data(), uvs.size() * sizeof(glm::vec2));
    out.triangleMaterial = gl::makeBuffer(materials.data(), materials.size() * sizeof(uint32_t));
    for (const AlphaMaterial& m : alpha.materials) {
        GpuSeeThrough::Material gm;
        gm.constant = m.constant;
        gm.textured = m.textured();
        if (gm.textured) {
            gm.texture = gl::Texture(m.width, m.height, GL_R32F,
                                     m.filter == AlphaFilter::Closest ? GL_NEAREST : GL_LINEAR);
            g.TextureSubImage2D(gm.texture.id(), 0, 0, 0, m.width, m.height, GL_RED, GL_FLOAT, m.texels.data());
            const GLint wrap = m.wrap == AlphaWrap::Repeat ? GL_REPEAT
                               : m.wrap == AlphaWrap::Extend ? GL_CLAMP_TO_EDGE
                                                             : GL_CLAMP_TO_BORDER;
            g.TextureParameteri(gm.texture.id(), GL_TEXTURE_WRAP_S, wrap);
            g.TextureParameteri(gm.texture.id(), GL_TEXTURE_WRAP_T, wrap);
            const float transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            g.TextureParameterfv(gm.texture.id(), GL_TEXTURE_BORDER_COLOR, transparent);
        }
        out.materials.push_back(std::move(gm));
    }
    g.check("uploading a see-through mesh's materials");
    return out;
}

}  // namespace ss
