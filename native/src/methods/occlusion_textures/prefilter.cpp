// How occlusion_textures picks, dispatches and binds a pre-filter, and owns its slice textures.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "methods/occlusion_textures/prefilter.h"

namespace ss::occlusion {

namespace {

// Each filter once: its setting name, the program define that picks its boxFilter() in the
// shaders, the target of its filtered textures and the stage that fills them.
struct FilterKind {
    Filter filter;
    const char* name;
    const char* define;
    GLenum target;
    void (*run)(const SliceTextures&, FilteredSlices&);
};
constexpr FilterKind kFilterKinds[] = {
    {Filter::Mipmap, "mipmap", "FILTER_MIPMAP", GL_TEXTURE_2D, prefilterMipmap},
    {Filter::NBuffer, "nbuffer", "FILTER_NBUFFER", GL_TEXTURE_2D_ARRAY, prefilterNBuffer},
    {Filter::Sat, "sat", "FILTER_SAT", GL_TEXTURE_2D_ARRAY, prefilterSat},
};

const FilterKind& kindOf(Filter filter) {
    for (const FilterKind& k : kFilterKinds)
        if (k.filter == filter) return k;
    fail(SS_ERROR_INTERNAL, "occlusion_textures: a filter without its table entry");
}

}  // namespace

Filter parseFilter(const std::string& name) {
    std::string known;
    for (const FilterKind& k : kFilterKinds) {
        if (name == k.name) return k.filter;
        known += std::string(known.empty() ? "" : ", ") + k.name;
    }
    fail(SS_ERROR_INVALID_ARGUMENT, "occlusion_textures: filter = '" + name + "' (known: " + known + ")");
}

const char* filterDefine(Filter filter) { return kindOf(filter).define; }

SliceTextures makeSliceTextures(int width, int height, int count, bool withMipmaps) {
    const gl::Functions& gl = gl::api();
    SliceTextures s;
    s.width = width;
    s.height = height;
    s.count = count;
    int levels = withMipmaps ? 1 + int(std::floor(std::log2(float(std::max(width, height))))) : 1;
    const float border[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int g = 0; g < (count + 3) / 4; ++g) {
        GLuint id = 0;
        gl.CreateTextures(GL_TEXTURE_2D, 1, &id);
        s.groups.emplace_back(id);
        gl.TextureStorage2D(id, levels, withMipmaps ? GL_RGBA16F : GL_RGBA8, width, height);
        // Outside the slicing frustum nothing occludes: sample the border as 0.
        gl.TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
        gl.TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
        gl.TextureParameterfv(id, GL_TEXTURE_BORDER_COLOR, border);
        gl.TextureParameteri(id, GL_TEXTURE_MIN_FILTER, withMipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
        gl.TextureParameteri(id, GL_TEXTURE_MAG_FILTER, withMipmaps ? GL_LINEAR : GL_NEAREST);

    }
    gl.check("creating the occlusion textures");
    return s;
}

FilteredSlices prefilter(Filter filter, const SliceTextures& slices) {
    const FilterKind& kind = kindOf(filter);
    FilteredSlices f;
    f.filter = filter;
    f.target = kind.target;
    f.width = slices.width;
    f.height = slices.height;
    kind.run(slices, f);
    if (filter != Filter::Sat) f.bounds = findSliceBounds(slices);  // SAT's row pass finds them
    return f;
}

void bindFiltered(const gl::Program& program, const FilteredSlices& filtered, int firstUnit) {
    if (filtered.filter == Filter::Sat) {
        program.setTexture("satTables", firstUnit, filtered.textures[0], GL_TEXTURE_2D_ARRAY);
        for (size_t k = 0; k < filtered.bounds.size(); ++k)
            program.set(("sliceBounds[" + std::to_string(k) + "]").c_str(), filtered.bounds[k]);
        program.set("satTexel", 1.0f / glm::vec2(float(filtered.width + 1), float(filtered.height + 1)));
        return;
    }
    static const char* names[4] = {"filtered[0]", "filtered[1]", "filtered[2]", "filtered[3]"};
    for (int g = 0; g < 4; ++g) {
        GLuint tex = filtered.textures[size_t(std::min(g, int(filtered.textures.size()) - 1))];
        program.setTexture(names[g], firstUnit + g, tex, filtered.target);
    }
}

std::vector<float> readTexture(GLuint texture, GLenum target, int level, int layer, int width, int height) {
    const gl::Functions& gl = gl::api();
    std::vector<float> out(size_t(width) * height * 4);
    if (target == GL_TEXTURE_2D_ARRAY)
        gl.GetTextureSubImage(texture, level, 0, 0, layer, width, height, 1, GL_RGBA, GL_FLOAT,
                              GLsizei(out.size() * sizeof(float)), out.data());
    else
        gl.GetTextureImage(texture, level, GL_RGBA, GL_FLOAT, GLsizei(out.size() * sizeof(float)), out.data());
    gl.check("reading an occlusion texture back");
    return out;
}

}  // namespace ss::occlusion
