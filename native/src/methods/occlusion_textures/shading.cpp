// How occlusion_textures shades the shared camera G-buffer.
// SPDX-License-Identifier: GPL-3.0-or-later
// One full-screen pass reading the pre-filtered slices, V and mask in one target, the per-slice
// shadows in four more.
#include <string>

#include "gl/framebuffer.h"
#include "gl/scratch_targets.h"
#include "methods/occlusion_textures/passes.h"
#include "pipeline/frame.h"

namespace ss::occlusion {

ShadeOutput shade(Frame& frame, int lightIndex, const SliceSetup& setup, const FilteredSlices& filtered,
                  Fade fade, bool sliceLayers) {
    const gl::Functions& gl = frame.gl();
    const CameraPass& camera = frame.cameraPass();
    int groups = sliceLayers ? (setup.count() + 3) / 4 : 0;
    std::vector<GLenum> formats(size_t(1 + groups), GL_RGBA32F);
    gl::Framebuffer& target = gl::scratchFramebuffer("occlusion_textures.shading", camera.width, camera.height, formats);

    gl::ProgramDesc desc;
    desc.vertex = "common/fullscreen.vert.glsl";
    desc.fragment = "occlusion_textures/shade.frag.glsl";
    // The slice count as a constant: see combine.glsl (one program variant per count in use).
    desc.defines = {filterDefine(filtered.filter), "SS_OT_SLICES=" + std::to_string(setup.count())};
    const gl::Program& program = gl::program(desc);
    program.use();
    int unit = frame.bindCameraPass(program, 0);
    frame.setLightUniforms(program, lightIndex);
    bindFiltered(program, filtered, unit);
    program.set("worldToLight", worldToLocal(setup.light));
    program.set("lightHalf", glm::vec2(setup.light.halfX, setup.light.halfY));
    program.set("copDistance", setup.d);
    for (int k = 0; k <= setup.count(); ++k)
        program.set(("planes[" + std::to_string(k) + "]").c_str(), setup.planes[size_t(k)]);
    program.set("sliceSize", glm::vec2(float(setup.width), float(setup.height)));
    program.set("fadeRule", fade == Fade::Paper ? 1 : 0);

    target.bind();
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_BLEND);
    frame.drawFullscreen();
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.check("shading occlusion_textures");

    ShadeOutput out;
    out.visibility = target.readChannel(0, 0);
    out.mask = target.readChannel(0, 1);
    for (int k = 0; k < (sliceLayers ? setup.count() : 0); ++k) out.slices.push_back(target.readChannel(1 + k / 4, k % 4));
    return out;
}

}  // namespace ss::occlusion
