// What the GL stages of occlusion_textures hand each other.
// SPDX-License-Identifier: GPL-3.0-or-later
// The packed occlusion textures (four slices per RGBA target) and their pre-filtered form, one per
// filter type.
#pragma once
#include <string>
#include <vector>

#include "gl/objects.h"
#include "gl/program.h"

#include <glm/glm.hpp>

namespace ss::occlusion {

enum class Filter { Mipmap, NBuffer, Sat };
// "mipmap", "nbuffer", "sat"; throws ss::Error(SS_ERROR_INVALID_ARGUMENT) otherwise.
Filter parseFilter(const std::string& name);
// The program define that picks the filter's boxFilter() in the shaders.
const char* filterDefine(Filter filter);

using TextureHandle = gl::Handle<gl::deleteTexture>;

// The slicing pass output: ceil(count / 4) RGBA16F textures of width x height; slice k is
// channel k % 4 of texture k / 4. With mipmap storage when the mipmap filter will run.
struct SliceTextures {
    int width = 0, height = 0, count = 0;
    std::vector<TextureHandle> groups;
    int groupCount() const { return int(groups.size()); }
};
SliceTextures makeSliceTextures(int width, int height, int count, bool withMipmaps);

// Pre-filtered textures. Mipmaps and N-Buffers: one per group, bound to the shaders'
// `filtered[4]` samplers. SAT: one array texture, layer k = slice k's table, bound to
// `satTables`; the array is the render thread's scratch texture (gl/scratch_targets.h), valid
// until the next prefilterSat there. Every filter also has each slice's occupied texels.
struct FilteredSlices {
    Filter filter = Filter::NBuffer;
    GLenum target = GL_TEXTURE_2D;  // GL_TEXTURE_2D_ARRAY for N-Buffers and SAT
    std::vector<TextureHandle> owned;  // N-Buffers (mipmaps live in the slices, SAT tables in scratch)
    std::vector<GLuint> textures;
    int width = 0, height = 0;  // of the slices (SAT tables are one texel larger)
    // Per slice: (min x, min y, max x + 1, max y + 1) of its occupied texels in texel units; an
    // empty slice has min > max.
    std::vector<glm::vec4> bounds;
};

// The slices' occupied bounds: a storage buffer the scans fill (slice_bounds.glsl; made bound
// for them), its read-back, and a scan of its own for the filters that do not scan every texel.
gl::BufferHandle makeSliceBoundsBuffer(int count);
std::vector<glm::vec4> readSliceBounds(const gl::BufferHandle& buffer, int count);
std::vector<glm::vec4> findSliceBounds(const SliceTextures& slices);

// The pre-filter `filter` over the slices, with every slice's occupied bounds.
FilteredSlices prefilter(Filter filter, const SliceTextures& slices);
// The stages prefilter() runs: each fills `f` (filter, target and size already set).
void prefilterMipmap(const SliceTextures& slices, FilteredSlices& f);
void prefilterSat(const SliceTextures& slices, FilteredSlices& f);
void prefilterNBuffer(const SliceTextures& slices, FilteredSlices& f);

// Points `filtered[0..3]` of `program` at the groups (units firstUnit..firstUnit+3; unused
// entries repeat group 0 so every sampler is valid), or for SAT `satTables` at the table array
// (unit firstUnit).
void bindFiltered(const gl::Program& program, const FilteredSlices& filtered, int firstUnit);

// Reads every level of one group texture back (tests and debug): RGBA floats, row 0 first.
std::vector<float> readTexture(GLuint texture, GLenum target, int level, int layer, int width, int height);

}  // namespace ss::occlusion
