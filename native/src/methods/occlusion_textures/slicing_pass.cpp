// How occlusion_textures slices the scene on the GPU.
// SPDX-License-Identifier: GPL-3.0-or-later
// One MAX-blended draw of the casters into up to four RGBA targets, four slices per target.
#include "gl/framebuffer.h"
#include "gl/render_state.h"
#include "methods/occlusion_textures/passes.h"
#include "scene_cache/scene_cache.h"

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

namespace {

void drawSlices(SceneCache& sceneCache, const SliceSetup& setup, SliceTextures& slices, bool thinFixAll,
                const std::optional<PixelRect>& rect) {
    const gl::Functions& gl = sceneCache.gl();
    gl::Framebuffer target(setup.width, setup.height, {});
    for (int g = 0; g < slices.groupCount(); ++g) target.attachColor(g, slices.groups[size_t(g)].id());
    target.bind();
    if (rect) {
        gl.Enable(GL_SCISSOR_TEST);
        gl.Scissor(rect->x0, rect->y0, rect->x1 - rect->x0, rect->y1 - rect->y0);
    }
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
    std::optional<PatchRegion> region;
    if (rect) region = PatchRegion{*rect, setup.worldToClip, setup.width, setup.height};
    sceneCache.drawMeshesWhere(program, SS_MESH_CAST, region, [&](const GpuMesh& mesh) {
        program.set("thinFix", (thinFixAll || (mesh.flags & SS_MESH_THIN)) ? 1 : 0);
        program.set("unsliced", setup.sliced(mesh.meshIndex) ? 0 : 1);
    }, setup.lightIndex, true);
    // See-through casters occlude their slice by their alpha (drawn whole; the scissor keeps
    // a patch's outside).
    const gl::Program& seeThrough = gl::program("occlusion_textures/slice_see_through.vert.glsl",
                                                "occlusion_textures/slice_see_through.frag.glsl");
    seeThrough.use();
    seeThrough.set("worldToClip", setup.worldToClip);
    seeThrough.set("worldToLight", worldToLocal(setup.light));
    seeThrough.set("firstPlane", setup.planes.front());
    seeThrough.set("thickness", (setup.planes.back() - setup.planes.front()) / float(setup.count()));
    seeThrough.set("sliceCount", setup.count());
    sceneCache.drawSeeThroughWhere(seeThrough, SS_MESH_CAST, [&](const GpuMesh& mesh) {
        seeThrough.set("thinFix", (thinFixAll || (mesh.flags & SS_MESH_THIN)) ? 1 : 0);
        seeThrough.set("unsliced", setup.sliced(mesh.meshIndex) ? 0 : 1);
    }, setup.lightIndex);
    gl.Disable(GL_SCISSOR_TEST);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.check("slicing the scene into occlusion textures");
}

}  // namespace

SliceTextures renderSlices(SceneCache& sceneCache, const SliceSetup& setup, Filter filter, bool thinFixAll) {
    SliceTextures slices = makeSliceTextures(setup.width, setup.height, setup.count(), filter == Filter::Mipmap);
    drawSlices(sceneCache, setup, slices, thinFixAll, std::nullopt);
    return slices;
}

void patchSlices(SceneCache& sceneCache, const SliceSetup& setup, SliceTextures& slices, bool thinFixAll, const PixelRect& rect) {
    drawSlices(sceneCache, setup, slices, thinFixAll, rect);
}

}  // namespace ss::occlusion
