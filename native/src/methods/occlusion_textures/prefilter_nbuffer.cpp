// How occlusion_textures pre-filters with N-Buffers: one compute pass per level.
// SPDX-License-Identifier: GPL-3.0-or-later
// Each texel the mean of four boxes of the level below, every level at full resolution in one array
// texture.
#include <algorithm>

#include "methods/occlusion_textures/prefilter.h"

namespace ss::occlusion {

void prefilterNBuffer(const SliceTextures& slices, FilteredSlices& f) {
    const gl::Functions& gl = gl::api();
    gl::ProgramDesc desc;
    desc.compute = "occlusion_textures/prefilter_nbuffer_level.comp.glsl";
    const gl::Program& level = gl::program(desc);
    // Levels 0 .. L with 2^L the first power of two covering the texture's long side.
    int levels = 1;
    while ((1 << (levels - 1)) < std::max(slices.width, slices.height)) ++levels;
    const float border[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (const TextureHandle& group : slices.groups) {
        GLuint id = 0;
        gl.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
        f.owned.emplace_back(id);
        f.textures.push_back(id);
        // Means of binary texels: 16-bit floats keep them to 1e-3 at half the memory.
        gl.TextureStorage3D(id, 1, GL_RGBA16F, slices.width, slices.height, levels);
        gl.TextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.TextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
        gl.TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
        gl.TextureParameterfv(id, GL_TEXTURE_BORDER_COLOR, border);

        level.use();
        level.setTexture("slices", 0, group.id());
        level.setTexture("levels", 1, id, GL_TEXTURE_2D_ARRAY);
        gl.BindImageTexture(0, id, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        for (int l = 0; l < levels; ++l) {
            level.set("level", l);
            gl.DispatchCompute(GLuint((slices.width + 7) / 8), GLuint((slices.height + 7) / 8), 1);
            gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        }
    }
    gl.BindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
    gl.check("building N-Buffers");
}

}  // namespace ss::occlusion
