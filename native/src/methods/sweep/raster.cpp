// How the shadow triangles are uploaded and rasterised with the camera's matrices, then resolved
// over the camera pass into V and mask.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/raster.h"

#include <cstddef>
#include <vector>

#include "gl/objects.h"
#include "gl/program.h"
#include "gl/render_state.h"
#include "gl/scratch_targets.h"

namespace ss {

namespace {

struct RasterVertex {
    float position[3];
    float intensity;
};

// No depth test: the resolve keeps only pixels whose camera-pass surface is the receiver mesh,
// and there the ray through the pixel centre meets the plane exactly where the shadow triangle
// covering that centre lies — anything in front already took the pixel in the camera pass.
// Plain overwrite: trapezoids tile the shadow, so no two triangles cover a pixel centre.
constexpr gl::RenderState kShadowMesh{"sweep_shadow_mesh", false, GL_ALWAYS, false, true, false,
                                      GL_FUNC_ADD, GL_ONE, GL_ZERO, GL_NONE};
// Light clusters: their meshes overlap and their (already weighted) intensities add up.
constexpr gl::RenderState kShadowMeshClusters{"sweep_shadow_mesh_clusters", false, GL_ALWAYS, false, true, true,
                                              GL_FUNC_ADD, GL_ONE, GL_ONE, GL_NONE};

}  // namespace

Layers drawSweepShadow(SceneCache& sceneCache, const SweepShadow& shadow, int lightIndex) {
    const gl::Functions& g = sceneCache.gl();
    const CameraPass& cam = sceneCache.cameraPass();
    gl::Framebuffer& drawn = gl::scratchFramebuffer("sweep.intensity", cam.width, cam.height, {GL_R32F});
    drawn.bind();
    gl::apply(shadow.parts.empty() ? kShadowMesh : kShadowMeshClusters);
    drawn.clearColor(0, glm::vec4(0.0f));
    std::vector<RasterVertex> verts;
    verts.reserve(shadow.mesh.indices.size());
    for (uint32_t i : shadow.mesh.indices) {
        glm::dvec3 w = shadow.worldVertex(i);
        verts.push_back({{float(w.x), float(w.y), float(w.z)}, shadow.mesh.vertices[i].intensity});
    }
    if (!verts.empty()) {
        gl::BufferHandle buffer = gl::makeBuffer(verts.data(), verts.size() * sizeof(RasterVertex));
        GLuint vao = 0;
        g.CreateVertexArrays(1, &vao);
        gl::VertexArrayHandle vaoHandle(vao);
        g.VertexArrayVertexBuffer(vao, 0, buffer.id(), 0, sizeof(RasterVertex));
        g.VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(RasterVertex, position));
        g.VertexArrayAttribFormat(vao, 1, 1, GL_FLOAT, GL_FALSE, offsetof(RasterVertex, intensity));
        for (GLuint a = 0; a < 2; ++a) {
            g.VertexArrayAttribBinding(vao, a, 0);
            g.EnableVertexArrayAttrib(vao, a);
        }
        const gl::Program& prog = gl::program("sweep/shadow_mesh.vert.glsl", "sweep/shadow_mesh.frag.glsl");
        prog.use();
        prog.set("uWorldToClip", sceneCache.camera().worldToClip());
        g.BindVertexArray(vao);
        g.DrawArrays(GL_TRIANGLES, 0, GLsizei(verts.size()));
        g.BindVertexArray(0);
    }
    g.check("drawing the sweep shadow mesh");

    gl::Framebuffer& out = gl::scratchFramebuffer("sweep.camera", cam.width, cam.height, {GL_RG32F});
    out.bind();
    gl::apply(gl::states::overwrite);
    const gl::Program& resolve = gl::program("common/fullscreen.vert.glsl", "sweep/resolve.frag.glsl");
    resolve.use();
    int unit = sceneCache.bindCameraPass(resolve);
    resolve.setTexture("uShadowIntensity", unit, drawn.colorId(0));
    sceneCache.setLightUniforms(resolve, lightIndex);
    resolve.set("uReceiverMesh", shadow.plane.mesh);
    sceneCache.drawFullscreen();
    g.BindFramebuffer(GL_FRAMEBUFFER, 0);
    g.check("resolving the sweep shadow");
    std::vector<Image> channels = out.readChannels(0, 2);
    Layers layers;
    layers.add("V", std::move(channels[0]));
    layers.add("mask", std::move(channels[1]));
    return layers;
}

}  // namespace ss
