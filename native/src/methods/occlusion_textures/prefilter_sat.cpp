// How occlusion_textures pre-filters with summed-area tables (two compute passes).
// SPDX-License-Identifier: GPL-3.0-or-later
// Running sums along rows (four slices at once, RGBA), then down columns into a (W+1) x (H+1)
// R32F table per slice (the layers of one array texture, so shading can pick a slice by index),
// plus each slice's occupied-texel bounds.
#include "gl/scratch_targets.h"
#include "methods/occlusion_textures/prefilter.h"

namespace ss::occlusion {

void prefilterSat(const SliceTextures& slices, FilteredSlices& f) {
    const gl::Functions& gl = gl::api();
    gl::ProgramDesc rowsDesc, columnsDesc;
    rowsDesc.compute = "occlusion_textures/prefilter_sat_rows.comp.glsl";
    columnsDesc.compute = "occlusion_textures/prefilter_sat_columns.comp.glsl";
    const gl::Program& rows = gl::program(rowsDesc);
    const gl::Program& columns = gl::program(columnsDesc);
    const int tw = slices.width + 1, th = slices.height + 1, layers = slices.count;

    // Kept between frames (gl/scratch_targets.h): fresh storage costs page faults on llvmpipe.
    const GLuint id = gl::scratchTextureArray("occlusion_textures.sat", tw, th, layers, GL_R32F);
    f.textures.push_back(id);

    gl::BufferHandle bounds = makeSliceBoundsBuffer(layers);

    // The row sums of one group at a time, four slices per texel (one store per texel).
    gl::Texture rowSums(tw, th, GL_RGBA32F);
    for (int g = 0; g < slices.groupCount(); ++g) {
        rows.use();
        rows.setTexture("slices", 0, slices.groups[size_t(g)].id());
        rows.set("firstSlice", 4 * g);
        rows.set("sliceCount", layers);
        gl.BindImageTexture(0, rowSums.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        gl.DispatchCompute(GLuint((th + 63) / 64), 1, 1);
        gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        columns.use();
        columns.set("firstSlice", 4 * g);
        columns.set("sliceCount", layers);
        gl.BindImageTexture(0, rowSums.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        gl.BindImageTexture(1, id, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        gl.DispatchCompute(GLuint((tw + 63) / 64), 1, 1);
        gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                     GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.BindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    gl.BindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    // Shading reads the bounds as uniforms (a constant-index uniform is a broadcast, a buffer
    // read a per-pixel gather on llvmpipe); shading waits for these passes anyway.
    f.bounds = readSliceBounds(bounds, layers);
    gl.check("building summed-area tables");
}

}  // namespace ss::occlusion
