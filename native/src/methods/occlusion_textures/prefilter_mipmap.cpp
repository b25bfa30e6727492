// How occlusion_textures pre-filters with mipmaps.
// SPDX-License-Identifier: GPL-3.0-or-later
// The GL texture unit builds the pyramid of all four packed slices at once; lookups are anisotropic
// trilinear (filter_mipmap.glsl).
#include "methods/occlusion_textures/prefilter.h"

namespace ss::occlusion {

void prefilterMipmap(const SliceTextures& slices, FilteredSlices& f) {
    const gl::Functions& gl = gl::api();
    for (const TextureHandle& t : slices.groups) {
        gl.GenerateTextureMipmap(t.id());
        f.textures.push_back(t.id());
    }
    gl.check("building occlusion texture mipmaps");
}

}  // namespace ss::occlusion
