// How occlusion_textures pre-filters with summed-area tables (two compute passes).
// SPDX-License-Identifier: GPL-3.0-or-later
// Running sums along rows, then down columns, into a (W+1) x (H+1) RGBA32F table per group of
// four slices.
#include "methods/occlusion_textures/gl.h"

namespace ss::occlusion {

FilteredSlices prefilterSat(const SliceTextures& slices) {
    const gl::Functions& gl = gl::api();
    FilteredSlices f;
    f.filter = Filter::Sat;
    f.target = GL_TEXTURE_2D;
    gl::ProgramDesc rowsDesc, columnsDesc;
    rowsDesc.compute = "occlusion_textures/prefilter_sat_rows.comp.glsl";
    columnsDesc.compute = "occlusion_textures/prefilter_sat_columns.comp.glsl";
    const gl::Program& rows = gl::program(rowsDesc);
    const gl::Program& columns = gl::program(columnsDesc);
    int tw = slices.width + 1, th = slices.height + 1;
    for (const TextureHandle& group : slices.groups) {
        GLuint id = 0;
        gl.CreateTextures(GL_TEXTURE_2D, 1, &id);
        f.owned.emplace_back(id);
        f.textures.push_back(id);
        gl.TextureStorage2D(id, 1, GL_RGBA32F, tw, th);
        gl.TextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl.TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

        rows.use();
        rows.setTexture("slices", 0, group.id());
        gl.BindImageTexture(0, id, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        gl.DispatchCompute(GLuint((th + 63) / 64), 1, 1);
        gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        columns.use();
        gl.BindImageTexture(0, id, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
        gl.DispatchCompute(GLuint((tw + 63) / 64), 1, 1);
        gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    }
    gl.BindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    gl.check("building summed-area tables");
    return f;
}

}  // namespace ss::occlusion
