// How the slices' occupied bounds are found and read back (shaders/occlusion_textures/slice_bounds.glsl).
// SPDX-License-Identifier: GPL-3.0-or-later
// A shader storage buffer the scans fill with atomics, read back as FilteredSlices::bounds.
#include <climits>

#include "methods/occlusion_textures/prefilter.h"

namespace ss::occlusion {

namespace {
constexpr GLuint kSliceBoundsBinding = 2;  // slice_bounds.glsl
}

gl::BufferHandle makeSliceBoundsBuffer(int count) {
    // Per slice min x, min y, max x, max y: empty (min > max) until a scan finds a texel.
    std::vector<int> empty;
    for (int k = 0; k < count; ++k) empty.insert(empty.end(), {INT_MAX, INT_MAX, -1, -1});
    gl::BufferHandle buffer = gl::makeBuffer(empty.data(), empty.size() * sizeof(int));
    gl::api().BindBufferBase(GL_SHADER_STORAGE_BUFFER, kSliceBoundsBinding, buffer.id());
    return buffer;
}

std::vector<glm::vec4> readSliceBounds(const gl::BufferHandle& buffer, int count) {
    const gl::Functions& gl = gl::api();
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<int> b(size_t(count) * 4);
    gl.GetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(b.size() * sizeof(int)), b.data());
    gl.check("reading the slices' bounds back");
    std::vector<glm::vec4> out;
    for (int k = 0; k < count; ++k) {
        const int* s = &b[size_t(4 * k)];
        out.push_back(s[0] > s[2] ? glm::vec4(1e30f, 1e30f, -1e30f, -1e30f)
                                  : glm::vec4(float(s[0]), float(s[1]), float(s[2] + 1), float(s[3] + 1)));
    }
    return out;
}

std::vector<glm::vec4> findSliceBounds(const SliceTextures& slices) {
    const gl::Functions& gl = gl::api();
    gl::ProgramDesc desc;
    desc.compute = "occlusion_textures/prefilter_bounds.comp.glsl";
    const gl::Program& scan = gl::program(desc);
    gl::BufferHandle buffer = makeSliceBoundsBuffer(slices.count);
    scan.use();
    scan.set("sliceCount", slices.count);
    for (int g = 0; g < slices.groupCount(); ++g) {
        scan.setTexture("slices", 0, slices.groups[size_t(g)].id());
        scan.set("firstSlice", 4 * g);
        gl.DispatchCompute(GLuint((slices.height + 63) / 64), 1, 1);
    }
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return readSliceBounds(buffer, slices.count);
}

}  // namespace ss::occlusion
