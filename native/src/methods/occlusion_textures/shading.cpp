// How occlusion_textures shades the shared camera G-buffer.
// SPDX-License-Identifier: GPL-3.0-or-later
// One full-screen pass reading the pre-filtered slices, V and mask in one target, the per-slice
// shadows in four more.
#include <string>

#include "gl/framebuffer.h"
#include "gl/render_state.h"
#include "gl/scratch_targets.h"
#include "methods/occlusion_textures/passes.h"
#include "pipeline/frame.h"

namespace ss::occlusion {

namespace {

const gl::Program& shadingProgram(Filter filter, int sliceCount, bool sliceLayers) {
    gl::ProgramDesc desc;
    desc.vertex = "common/fullscreen.vert.glsl";
    desc.fragment = "occlusion_textures/shade.frag.glsl";
    // The slice count as a constant: see combine.glsl (one program variant per count in use).
    desc.defines = {filterDefine(filter), "SS_OT_SLICES=" + std::to_string(sliceCount)};
    if (sliceLayers) desc.defines.push_back("SS_OT_SLICE_LAYERS");
    return gl::program(desc);
}

void setShadingUniforms(Frame& frame, const gl::Program& program, int lightIndex, const SliceSetup& setup,
                        const FilteredSlices& filtered, Fade fade, bool skipEmptySlices) {
    program.use();
    int unit = frame.bindCameraPass(program, 0);
    frame.setLightUniforms(program, lightIndex);
    bindFiltered(program, filtered, unit);
    program.set("worldToLight", worldToLocal(setup.light));
    const glm::vec2 texels(float(setup.width), float(setup.height));
    const glm::vec2 lightHalf(setup.light.halfX, setup.light.halfY);
    for (int k = 0; k < setup.count(); ++k) {
        const float top = setup.planes[size_t(k)], bottom = setup.planes[size_t(k) + 1];
        const float project = setup.d / (setup.d + bottom);  // the COP's scale at the lower plane
        const std::string index = "[" + std::to_string(k) + "]";
        program.set(("sliceDepths" + index).c_str(), glm::vec4(top, bottom, 1.0f / (bottom - top), 0.0f));
        program.set(("sliceScales" + index).c_str(),
                    glm::vec4(bottom * project * 0.5f * texels / lightHalf, project * texels));
    }
    program.set("sliceSize", texels);
    program.set("skipEmptySlices", skipEmptySlices ? 1 : 0);
    program.set("fadeRule", fade == Fade::Paper ? 1 : 0);
}

}  // namespace

ShadeOutput shade(Frame& frame, int lightIndex, const SliceSetup& setup, const FilteredSlices& filtered,
                  Fade fade, bool sliceLayers, bool skipEmptySlices) {
    const gl::Functions& gl = frame.gl();
    const CameraPass& camera = frame.cameraPass();
    int groups = sliceLayers ? (setup.count() + 3) / 4 : 0;
    // V and mask in an RG target (half the bytes to write and read back), the slices in RGBA.
    std::vector<GLenum> formats(size_t(1 + groups), GL_RGBA32F);
    formats[0] = GL_RG32F;
    gl::Framebuffer& target = gl::scratchFramebuffer("occlusion_textures.shading", camera.width, camera.height, formats);
    target.bind();
    gl::apply(gl::states::overwrite);
    const gl::Program& program = shadingProgram(filtered.filter, setup.count(), sliceLayers);
    setShadingUniforms(frame, program, lightIndex, setup, filtered, fade, skipEmptySlices);
    frame.drawFullscreen();
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.check("shading occlusion_textures");

    ShadeOutput out;
    std::vector<Image> vm = target.readChannels(0, 2);
    out.visibility = std::move(vm[0]);
    out.mask = std::move(vm[1]);
    for (int k = 0; k < (sliceLayers ? setup.count() : 0); ++k) out.slices.push_back(target.readChannel(1 + k / 4, k % 4));
    return out;
}

}  // namespace ss::occlusion
