// How occlusion_textures shades the shared camera G-buffer.
// SPDX-License-Identifier: GPL-3.0-or-later
// A full-screen pass reading the pre-filtered slices, V and mask in one target, the per-slice
// shadows in four more, behind a classifying pass that marks the pixels to shade.
#include <algorithm>
#include <string>

#include "gl/framebuffer.h"
#include "gl/render_state.h"
#include "gl/scratch_targets.h"
#include "methods/occlusion_textures/passes.h"
#include "scene_cache/scene_cache.h"

namespace ss::occlusion {

namespace {

// The two shading passes (shading below): the first marks, at depth 0, the pixels a slice may
// shadow; the second shades only there (its triangle lies at depth 0.5).
constexpr gl::RenderState kMarkSlices{"occlusion_mark_slices", true, GL_ALWAYS, true, true, false,
                                      GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE};
constexpr gl::RenderState kWhereMarked{"occlusion_where_marked", true, GL_GREATER, false, true, false,
                                       GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE};

const gl::Program& shadingProgram(Filter filter, int sliceCount, bool sliceLayers, bool classify) {
    gl::ProgramDesc desc;
    desc.vertex = "common/fullscreen.vert.glsl";
    desc.fragment = "occlusion_textures/shade.frag.glsl";
    // The slice count as a constant: see combine.glsl (one program variant per count in use).
    desc.defines = {filterDefine(filter), "SS_OT_SLICES=" + std::to_string(sliceCount)};
    if (sliceLayers) desc.defines.push_back("SS_OT_SLICE_LAYERS");
    if (classify) desc.defines.push_back("SS_OT_CLASSIFY");
    return gl::program(desc);
}

// The classifying pass's bounds over every non-empty slice (combine.glsl, maySliceShadow).
void setReachUniforms(const gl::Program& program, const SliceSetup& setup, const FilteredSlices& filtered, Fade fade,
                      bool skipEmptySlices) {
    const glm::vec2 texels(float(setup.width), float(setup.height));
    const glm::vec2 lightHalf(setup.light.halfX, setup.light.halfY);
    glm::vec4 rect(1e30f, 1e30f, -1e30f, -1e30f), scale(1e30f, 1e30f, -1e30f, -1e30f);
    glm::vec4 depth(1e30f, 1e30f, -1e30f, 0.0f);
    glm::vec2 half(0.0f);
    for (int k = 0; k < setup.count(); ++k) {
        const glm::vec4& b = filtered.bounds[size_t(k)];
        const float top = setup.planes[size_t(k)], bottom = setup.planes[size_t(k) + 1];
        // Left out: empty slices, and slices below every receiver, whose weight stays under the
        // 1e-4 that slicesToRead asks for at any receiver (e.g. the ground's own slice; 1e-6 of
        // the depth for the G-buffer's rounding).
        const float start = fade == Fade::Paper ? top : bottom;
        const bool belowReceivers = start >= setup.receiverDepthMax * (1.0f + 1e-6f) - 1e-4f * (bottom - top);
        if (b.x > b.z || belowReceivers) continue;
        const glm::vec2 ndc = setup.ndcPerUnit(bottom);
        const glm::vec2 centreScale = bottom * ndc * 0.5f * texels;
        rect = glm::vec4(glm::min(glm::vec2(rect), glm::vec2(b)), glm::max(glm::vec2(rect.z, rect.w), glm::vec2(b.z, b.w)));
        scale = glm::vec4(glm::min(glm::vec2(scale), centreScale), glm::max(glm::vec2(scale.z, scale.w), centreScale));
        depth = glm::vec4(std::min(depth.x, start), std::min(depth.y, bottom), std::max(depth.z, bottom), 0.0f);
        half = glm::max(half, 0.5f * lightHalf * ndc * texels);
    }
    if (!skipEmptySlices) {  // every pixel goes to the full pass
        rect = glm::vec4(-1e30f, -1e30f, 1e30f, 1e30f);
        depth.x = -1e30f;
    }
    program.set("reachRect", rect);
    program.set("reachScale", scale);
    program.set("reachDepth", depth);
    program.set("reachHalf", half);
    // The SAT reads its box exactly. An N-Buffer lookup reads squares of up to twice the short side
    // S around probes spread over the long side L, bilinearly: within L/2 + S + 1 <= 3 L/2 + 1.
    // A mipmap lookup reads 2x2 texels of a level up to 2 max(S, L/16) wide around each probe:
    // within L/2 + 2L = 5 L/2 (filter_nbuffer.glsl, filter_mipmap.glsl).
    glm::vec3 spread(1.0f, 0.0f, 0.0f);
    if (filtered.filter == Filter::NBuffer) spread = glm::vec3(3.0f, 2.0f, 1.0f);
    if (filtered.filter == Filter::Mipmap) spread = glm::vec3(5.0f, 2.0f, 1.0f);
    program.set("reachSpread", spread);
}

void setShadingUniforms(SceneCache& sceneCache, const gl::Program& program, int lightIndex, const SliceSetup& setup,
                        const FilteredSlices& filtered, Fade fade, bool skipEmptySlices) {
    program.use();
    int unit = sceneCache.bindCameraPass(program, 0);
    sceneCache.setLightUniforms(program, lightIndex);
    bindFiltered(program, filtered, unit);
    program.set("worldToLight", worldToLocal(setup.light));
    const glm::vec2 texels(float(setup.width), float(setup.height));
    const glm::vec2 lightHalf(setup.light.halfX, setup.light.halfY);
    for (int k = 0; k < setup.count(); ++k) {
        const float top = setup.planes[size_t(k)], bottom = setup.planes[size_t(k) + 1];
        const glm::vec2 ndc = setup.ndcPerUnit(bottom);  // the slicing camera's scale at the lower plane
        const std::string index = "[" + std::to_string(k) + "]";
        program.set(("sliceDepths" + index).c_str(), glm::vec4(top, bottom, 1.0f / (bottom - top), 0.0f));
        program.set(("sliceScales" + index).c_str(),
                    glm::vec4(bottom * ndc * 0.5f * texels, lightHalf * ndc * texels));
        // Where the slicing camera flattens an upper-plane point onto the lower plane:
        // lower = m upper + (0, 0, oz) (lookup_common.glsl, clippedLookup).
        const float m = setup.projection == Projection::Orthographic ? 1.0f : (bottom + setup.d) / (top + setup.d);
        const float oz = setup.projection == Projection::Orthographic ? bottom - top : (m - 1.0f) * setup.d;
        program.set(("sliceProjections" + index).c_str(), glm::vec2(m, oz));
    }
    program.set("sliceSize", texels);
    program.set("lightHalfSize", lightHalf);
    program.set("skipEmptySlices", skipEmptySlices ? 1 : 0);
    setReachUniforms(program, setup, filtered, fade, skipEmptySlices);
    program.set("fadeRule", fade == Fade::Paper ? 1 : 0);
}

}  // namespace

ShadeOutput shade(SceneCache& sceneCache, int lightIndex, const SliceSetup& setup, const FilteredSlices& filtered,
                  Fade fade, bool sliceLayers, bool skipEmptySlices) {
    const gl::Functions& gl = sceneCache.gl();
    const CameraPass& camera = sceneCache.cameraPass();
    int groups = sliceLayers ? (setup.count() + 3) / 4 : 0;
    // V and mask in an RG target (half the bytes to write and read back), the slices in RGBA.
    std::vector<GLenum> formats(size_t(1 + groups), GL_RGBA32F);
    formats[0] = GL_RG32F;
    gl::Framebuffer& target = gl::scratchFramebuffer("occlusion_textures.shading", camera.width, camera.height,
                                                     formats, GL_DEPTH_COMPONENT32F);
    target.bind();
    // Every pixel lit, depth 0 where a slice may shadow it (shade.frag.glsl)...
    gl::apply(kMarkSlices);
    const gl::Program& marks = shadingProgram(filtered.filter, setup.count(), sliceLayers, true);
    setShadingUniforms(sceneCache, marks, lightIndex, setup, filtered, fade, skipEmptySlices);
    sceneCache.drawFullscreen();
    // ...then the full pass there only: its triangle lies at depth 0.5.
    gl::apply(kWhereMarked);
    const gl::Program& program = shadingProgram(filtered.filter, setup.count(), sliceLayers, false);
    setShadingUniforms(sceneCache, program, lightIndex, setup, filtered, fade, skipEmptySlices);
    sceneCache.drawFullscreen();
    gl::apply(gl::states::overwrite);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.check("shading occlusion_textures");

    ShadeOutput out;
    std::vector<Image> vm = target.readChannels(0, 2);
    out.visibility = std::move(vm[0]);
    out.mask = std::move(vm[1]);
    // Slice k is channel k % 4 of attachment 1 + k / 4: one read-back per attachment.
    for (int group = 0; sliceLayers && group * 4 < setup.count(); ++group) {
        std::vector<Image> four = target.readChannels(1 + group, std::min(4, setup.count() - group * 4));
        for (Image& slice : four) out.slices.push_back(std::move(slice));
    }
    return out;
}

}  // namespace ss::occlusion
