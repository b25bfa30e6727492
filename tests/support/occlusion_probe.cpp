// How the tests reach the GL pre-filters directly: upload a slice group, probe boxFilter().
// SPDX-License-Identifier: GPL-3.0-or-later
#include "occlusion_probe.h"

#include "core/error.h"

namespace ss::occlusion {

void uploadGroup(const SliceTextures& slices, int group, const std::vector<float>& rgba) {
    const gl::Functions& gl = gl::api();
    if (rgba.size() != size_t(slices.width) * slices.height * 4)
        fail(SS_ERROR_INVALID_ARGUMENT, "occlusion_textures: upload size does not match the slices");
    gl.TextureSubImage2D(slices.groups[size_t(group)].id(), 0, 0, 0, slices.width, slices.height, GL_RGBA,
                         GL_FLOAT, rgba.data());
    gl.check("uploading an occlusion texture");
}

std::vector<glm::vec4> probeFilter(const FilteredSlices& filtered, int group, const std::vector<glm::vec4>& queries) {
    const gl::Functions& gl = gl::api();
    int n = int(queries.size());
    gl::Texture input(n, 1, GL_RGBA32F);
    gl.TextureSubImage2D(input.id(), 0, 0, 0, n, 1, GL_RGBA, GL_FLOAT, queries.data());
    gl::Texture output(n, 1, GL_RGBA32F);
    GLuint fbo = 0;
    gl.CreateFramebuffers(1, &fbo);
    gl::FramebufferHandle fboHandle(fbo);
    gl.NamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, output.id(), 0);
    GLuint vao = 0;
    gl.CreateVertexArrays(1, &vao);
    gl::VertexArrayHandle vaoHandle(vao);

    gl::ProgramDesc desc;
    desc.vertex = "occlusion_textures/probe.vert.glsl";
    desc.fragment = "occlusion_textures/probe.frag.glsl";
    desc.defines = {filterDefine(filtered.filter)};
    const gl::Program& program = gl::program(desc);
    program.use();
    bindFiltered(program, filtered, 1);
    program.setTexture("queries", 0, input.id());
    program.set("group", group);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.Viewport(0, 0, n, 1);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_DEPTH_TEST);
    gl.BindVertexArray(vao);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.BindVertexArray(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    std::vector<glm::vec4> out(static_cast<size_t>(n));
    gl.GetTextureImage(output.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(out.size() * sizeof(glm::vec4)), out.data());
    gl.check("probing the occlusion texture filter");
    return out;
}

}  // namespace ss::occlusion
