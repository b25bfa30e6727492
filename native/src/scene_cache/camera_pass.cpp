// How the camera pass is drawn, patched after moves and read back.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/camera_pass.h"

#include <algorithm>
#include <string>

#include "core/mesh_alpha.h"
#include "core/split_two.h"
#include "core/stopwatch.h"
#include "gl/program.h"
#include "gl/render_state.h"
#include "scene_cache/shader_uniforms.h"

namespace ss {

void CameraPassCache::dropStale(const Scene& scene) {
    if (pass_ && camera_ != scene.cameraVersion()) pass_.reset();
    if (pass_ && geometry_ != scene.geometryVersion()) images_.reset();  // get() patches the pass
    if (!pass_) images_.reset();
}

void CameraPassCache::listCoveringTriangles(const Camera& camera, const PixelRect& rect,
                                            const MeshDraws& draws) {
    const std::vector<GpuMesh>& meshes = draws.meshes;
    // The runs of triangles to test: per mesh, its consecutive clusters that reach the rectangle.
    struct Run {
        size_t mesh;
        uint32_t first, count;
        size_t start;  // in the sequence of tested triangles
    };
    const PatchRegion region{rect, camera.worldToClip(), camera.width, camera.height};
    std::vector<Run> runs;
    size_t tested = 0;
    for (size_t i = 0; i < meshes.size(); ++i) {
        const GpuMesh& m = meshes[i];
        if (m.indexCount == 0) continue;
        for (const GpuMesh::Cluster& c : m.clusters) {
            if (!reachesRegion(region, m, c.bounds)) continue;
            if (!runs.empty() && runs.back().mesh == i &&
                runs.back().first + runs.back().count == c.firstTriangle)
                runs.back().count += c.triangleCount;
            else runs.push_back(Run{i, c.firstTriangle, c.triangleCount, tested});
            tested += c.triangleCount;
        }
    }
    // Two halves of the sequence, each with its own scratch: listed_[0] then listed_[1] is the
    // list in order, mesh after mesh.
    std::vector<size_t> perMesh[2] = {std::vector<size_t>(meshes.size(), 0),
                                      std::vector<size_t>(meshes.size(), 0)};
    listed_[0].clear();
    listed_[1].clear();
    if (culling_ == CameraCulling::Auto) {
        const GLubyte* name = gl::api().GetString(GL_RENDERER);
        const std::string renderer = name ? reinterpret_cast<const char*>(name) : "";
        culling_ = renderer.find("llvmpipe") != std::string::npos ? CameraCulling::EachTriangle
                                                                  : CameraCulling::Clusters;
    }
    if (culling_ == CameraCulling::Clusters)
        for (const Run& run : runs) {
            for (uint32_t t = run.first; t < run.first + run.count; ++t) listed_[0].push_back(t);
            perMesh[0][run.mesh] += run.count;
        }
    auto testEach = [&](size_t begin, size_t end) {
        const int part = begin == 0 ? 0 : 1;
        std::vector<uint32_t>& out = listed_[part];
        size_t mesh = meshes.size();
        for (const Run& run : runs) {
            const size_t from = std::max(begin, run.start), to = std::min(end, run.start + run.count);
            if (from >= to) continue;
            const GpuMesh& m = meshes[run.mesh];
            const Mesh& sceneMesh = draws.scene.meshes()[size_t(m.meshIndex)];
            if (run.mesh != mesh) {
                coverage_[part].beginMesh(CoverageView{camera.worldToClip(), m.transformed, m.objectToWorld,
                                                       camera.width, camera.height, rect},
                                          sceneMesh.objectPositions);
                mesh = run.mesh;
            }
            const size_t before = out.size();
            coverage_[part].append(sceneMesh.triangles, run.first + uint32_t(from - run.start),
                                   uint32_t(to - from), out);
            perMesh[part][run.mesh] += out.size() - before;
        }
    };
    if (culling_ == CameraCulling::EachTriangle) splitTwo(tested, testEach);
    listedRanges_.clear();
    size_t first = 0;
    for (size_t i = 0; i < meshes.size(); ++i) {
        const size_t count = perMesh[0][i] + perMesh[1][i];
        listedRanges_.emplace_back(first, count);
        first += count;
    }
}

void CameraPassCache::draw(CameraPass& pass, const std::optional<PixelRect>& rect, const MeshDraws& draws) {
    const gl::Functions& g = gl::api();
    const Camera& cam = draws.scene.camera();
    listCoveringTriangles(cam, rect ? *rect : PixelRect{0, 0, pass.width, pass.height}, draws);
    const size_t listed = listed_[0].size() + listed_[1].size();
    draws.stats.cameraPassTriangles += listed;
    if (rect) draws.stats.patchTriangles += listed;
    if (listed > listedCapacity_) {
        listedCapacity_ = listed + listed / 4;
        listedBuffer_ = gl::makeBuffer(nullptr, listedCapacity_ * sizeof(uint32_t), true);
    }
    const GLsizeiptr bytes0 = GLsizeiptr(listed_[0].size() * sizeof(uint32_t));
    if (!listed_[0].empty()) g.NamedBufferSubData(listedBuffer_.id(), 0, bytes0, listed_[0].data());
    if (!listed_[1].empty())
        g.NamedBufferSubData(listedBuffer_.id(), bytes0, GLsizeiptr(listed_[1].size() * sizeof(uint32_t)),
                             listed_[1].data());

    const gl::Framebuffer& fb = pass.framebuffer;
    fb.bind();
    scissorTo(g, rect);
    fb.clearColor(0, glm::vec4(0.0f));
    fb.clearColor(1, glm::vec4(0.0f));
    fb.clearColor(2, glm::vec4(-1.0f, -1.0f, 0.0f, 0.0f));
    fb.clearDepth(1.0f);
    gl::apply(gl::states::opaque);

    // Meshes the camera may see through (a cut-out's holes) are drawn with the alpha-tested
    // variant, one material at a time as MeshDraws::drawSeeThroughWhere draws them.
    const gl::Program& opaque = gl::program("camera/gbuffer.vert.glsl", "camera/gbuffer.frag.glsl");
    const gl::Program& seeThrough =
        gl::program("camera/gbuffer.vert.glsl", "camera/gbuffer.frag.glsl", {"SEE_THROUGH"});
    const glm::mat4 cameraToWorld = glm::inverse(cam.worldToCamera);
    for (const gl::Program* prog : {&seeThrough, &opaque}) {
        prog->set("uWorldToClip", cam.worldToClip());
        prog->set("uWorldToView", cam.worldToCamera);
        prog->set("uCameraPosition", glm::vec3(cameraToWorld[3]));
        prog->set("uCameraForward", glm::normalize(-glm::vec3(cameraToWorld[2])));
        prog->set("uOrthographic", cam.isOrthographic() ? 1 : 0);
    }
    seeThrough.set("uCameraAlphaThreshold", kCameraAlphaThreshold);
    const gl::Program* inUse = &opaque;
    opaque.use();
    draws.emptyVertexArray.bind();
    if (listed > 0) g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, listedBuffer_.id());
    for (size_t i = 0; i < draws.meshes.size(); ++i) {
        const auto [first, count] = listedRanges_[i];
        if (count == 0) continue;
        const GpuMesh& m = draws.meshes[i];
        if (m.flags & SS_MESH_CAMERA_HIDDEN) continue;  // the camera sees past it
        const bool alphaTested = m.seeThrough && m.seeThrough->cameraSeesThrough;
        const gl::Program& prog = alphaTested ? seeThrough : opaque;
        if (&prog != inUse) prog.use(), inUse = &prog;
        setPlacementUniforms(prog, m);
        prog.set("uMeshIndex", m.meshIndex);
        prog.set("uReceives", m.receives() ? 1.0f : 0.0f);
        bindMeshStorage(g, m);
        if (!alphaTested) {
            g.DrawArrays(GL_TRIANGLES, GLint(3 * first), GLsizei(3 * count));
            continue;
        }
        for (size_t k = 0; k < m.seeThrough->materials.size(); ++k) {
            const GpuSeeThrough::Material& mat = m.seeThrough->materials[k];
            if (!mat.textured && mat.constant < kCameraAlphaThreshold) continue;  // the camera sees past it
            setAlphaMaterialUniforms(prog, mat, uint32_t(k));
            g.DrawArrays(GL_TRIANGLES, GLint(3 * first), GLsizei(3 * count));
        }
    }
    g.BindVertexArray(0);
    g.Disable(GL_SCISSOR_TEST);
    g.BindFramebuffer(GL_FRAMEBUFFER, 0);
    g.check("drawing the camera pass");
}

const CameraPass& CameraPassCache::get(const MeshDraws& draws) {
    const Scene& scene = draws.scene;
    if (pass_ && geometry_ == scene.geometryVersion()) return *pass_;
    const auto start = Clock::now();
    const Camera& cam = scene.camera();
    std::vector<MeshPlacement> now = placementsOf(scene);
    if (pass_) {
        // Only moves since it was drawn: redrawn where the moved meshes were and are.
        std::optional<std::vector<Bounds>> moved = movedBoxes(placements_, now);
        std::optional<PixelRect> rect;
        if (moved) rect = boxesOnScreen(*moved, cam.worldToClip(), pass_->width, pass_->height);
        if (rect) {
            if (!rect->empty()) draw(*pass_, rect, draws);
            ++draws.stats.cameraPassesPatched;
        } else {
            draw(*pass_, std::nullopt, draws);
        }
    } else {
        auto pass = std::make_unique<CameraPass>();
        pass->width = cam.width;
        pass->height = cam.height;
        pass->framebuffer =
            gl::Framebuffer(cam.width, cam.height, {GL_RGBA32F, GL_RGBA32F, GL_RG32F}, GL_DEPTH_COMPONENT32F);
        draw(*pass, std::nullopt, draws);
        pass_ = std::move(pass);
    }
    gl::api().Finish();
    receiversInView_.reset();
    draws.stats.cameraPassMs += msSince(start);
    ++draws.stats.cameraPasses;
    placements_ = std::move(now);
    camera_ = scene.cameraVersion();
    geometry_ = scene.geometryVersion();
    return *pass_;
}

const CameraImages& CameraPassCache::images(const MeshDraws& draws) {
    if (images_) return *images_;
    const CameraPass& pass = get(draws);
    auto img = std::make_unique<CameraImages>();
    img->width = pass.width;
    img->height = pass.height;
    img->positionDepth = pass.framebuffer.readRgba(0);
    img->normalReceive = pass.framebuffer.readRgba(1);
    img->ids = pass.framebuffer.readRgba(2);
    ++draws.stats.cameraReadbacks;
    images_ = std::move(img);
    return *images_;
}

void CameraPassCache::trimImages(size_t keepBytes) {
    if (images_ && size_t(images_->width) * size_t(images_->height) * 3 * sizeof(glm::vec4) > keepBytes)
        images_.reset();
}

}  // namespace ss
