// How occlusion_textures slices the scene on the GPU.
// SPDX-License-Identifier: GPL-3.0-or-later
// One MAX-blended draw of the casters into up to four RGBA targets, four slices per target.
#include "gl/framebuffer.h"
#include "gl/render_state.h"
#include "methods/occlusion_textures/passes.h"
#include "frame/frame.h"

namespace ss::occlusion {

glm::mat4 worldToLocal(const KernelLight& l) {
    glm::mat4 m(1.0f);
    for (int c = 0; c < 3; ++c) {
        m[c][0] = l.axisX[c];
        m[c][1] = l.axisY[c];
        m[c][2] = l.normal[c];
    }
    m[3] = glm::vec4(-glm::dot(l.axisX, l.centre), -glm::dot(l.axisY, l.centre), -glm::dot(l.normal, l.centre), 1.0f);
    return m;
}

SliceTextures renderSlices(Frame& frame, const SliceSetup& setup, Filter filter, bool thinFixAll) {
    const gl::Functions& gl = frame.gl();
    SliceTextures slices = makeSliceTextures(setup.width, setup.height, setup.count(), filter == Filter::Mipmap);
    gl::Framebuffer target(setup.width, setup.height, {});
    for (int g = 0; g < slices.groupCount(); ++g) target.attachColor(g, slices.groups[size_t(g)].id());
    target.bind();
    for (int g = 0; g < slices.groupCount(); ++g) target.clearColor(g, glm::vec4(0.0f));

    const gl::Program& program = gl::program("occlusion_textures/slice.vert.glsl", "occlusion_textures/slice.frag.glsl");
    program.use();
    program.set("worldToClip", setup.worldToClip);
    program.set("worldToLight", worldToLocal(setup.light));
    program.set("firstPlane", setup.planes.front());
    program.set("thickness", (setup.planes.back() - setup.planes.front()) / float(setup.count()));
    program.set("sliceCount", setup.count());
    // Every face counts (an occluder blocks light whichever way it faces), no depth test: a
    // texel of a slice is occluded when anything of that slice projects onto it.
    gl::apply(gl::states::maximum);
    frame.drawMeshes(program, SS_MESH_CAST, [&](const GpuMesh& mesh) {
        program.set("thinFix", (thinFixAll || (mesh.flags & SS_MESH_THIN)) ? 1 : 0);
    });
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.check("slicing the scene into occlusion textures");
    return slices;
}

}  // namespace ss::occlusion
