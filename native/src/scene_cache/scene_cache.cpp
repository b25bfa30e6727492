// How the shared passes are drawn once per frame: mesh upload, camera G-buffer, shadow maps.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/scene_cache.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/split_two.h"
#include "core/stopwatch.h"
#include "gl/render_state.h"

namespace ss {

bool GpuMesh::casts() const { return (flags & SS_MESH_CAST) != 0; }
bool GpuMesh::receives() const { return (flags & SS_MESH_RECEIVE) != 0; }

SceneCache::SceneCache(const Scene& scene) : scene_(&scene) {}
SceneCache::~SceneCache() = default;

const Light& SceneCache::light(int index) const { return scene_->light(index); }

const gl::Functions& SceneCache::gl() const { return gl::api(); }

std::vector<MeshPlacement> SceneCache::placements() const {
    std::vector<MeshPlacement> out;
    for (const Mesh& m : scene_->meshes()) {
        MeshPlacement p;
        p.shapeVersion = m.shapeVersion;
        p.objectToWorld = m.objectToWorld;
        for (const glm::vec3& v : m.positions) p.bounds.extend(v);
        out.push_back(p);
    }
    return out;
}

void SceneCache::dropStalePasses() {
    const uint64_t geometry = scene_->geometryVersion();
    if (camera_ && cameraPassCamera_ != scene_->cameraVersion()) camera_.reset();
    if (camera_ && cameraPassGeometry_ != geometry) cameraImages_.reset();  // cameraPass() patches the pass
    if (!camera_) cameraImages_.reset();
    if (shadowMapsGeometry_ != geometry) {
        std::vector<MeshPlacement> now = placements();
        const Bounds bounds = scene_->bounds();
        std::optional<std::vector<Bounds>> moved = movedBoxes(shadowMapPlacements_, now);
        // A map is fit to the scene bounds: when they change, so does every map's frustum.
        const bool sameFit = bounds.lo == shadowMapBounds_.lo && bounds.hi == shadowMapBounds_.hi;
        if (moved && sameFit) {
            for (auto& entry : shadowMaps_)
                entry.second.pending.insert(entry.second.pending.end(), moved->begin(), moved->end());
        } else {
            for (auto& entry : shadowMaps_) stats_.shadowMapBytes -= entry.second.bytes;
            shadowMaps_.clear();
        }
        shadowMapPlacements_ = std::move(now);
        shadowMapBounds_ = bounds;
        shadowMapsGeometry_ = geometry;
    }
}

namespace {

// Mesh::objectFaceNormals as vec4, the SSBO's layout.
std::vector<glm::vec4> faceNormalBuffer(const Mesh& mesh) {
    std::vector<glm::vec4> normals;
    for (const glm::vec3& n : mesh.objectFaceNormals) normals.emplace_back(n, 0.0f);
    return normals;
}

std::vector<GpuMesh::Cluster> clustersOf(const Mesh& mesh) {
    const std::vector<glm::vec3>& p = mesh.objectPositions;
    std::vector<GpuMesh::Cluster> clusters;
    for (size_t first = 0; first < mesh.triangles.size(); first += GpuMesh::kClusterTriangles) {
        GpuMesh::Cluster c;
        c.firstTriangle = uint32_t(first);
        c.triangleCount = uint32_t(std::min<size_t>(GpuMesh::kClusterTriangles, mesh.triangles.size() - first));
        for (size_t f = first; f < first + c.triangleCount; ++f)
            for (int k = 0; k < 3; ++k) c.bounds.extend(p[mesh.triangles[f][k]]);
        clusters.push_back(c);
    }
    return clusters;
}

void place(GpuMesh& gm, const Mesh& mesh) {
    gm.objectToWorld = mesh.objectToWorld;
    gm.transformed = mesh.transformed();
    gm.normalToWorld = glm::mat4(glm::transpose(glm::inverse(glm::mat3(mesh.objectToWorld))));
}

}  // namespace

const std::vector<GpuMesh>& SceneCache::meshes() {
    if (meshesGeometryVersion_ == scene_->geometryVersion()) return meshes_;
    const auto start = Clock::now();
    const gl::Functions& g = gl();
    const auto& src = scene_->meshes();
    std::map<uint64_t, GpuMesh> uploaded;
    for (GpuMesh& gm : meshes_) uploaded.emplace(gm.shapeVersion, std::move(gm));
    meshes_.clear();
    meshes_.reserve(src.size());
    for (size_t i = 0; i < src.size(); ++i) {
        const Mesh& mesh = src[i];
        auto kept = uploaded.find(mesh.shapeVersion);
        if (kept != uploaded.end()) {
            kept->second.meshIndex = int(i);
            place(kept->second, mesh);
            meshes_.push_back(std::move(kept->second));
            uploaded.erase(kept);
            continue;
        }
        const std::vector<glm::vec3>& positions = mesh.objectPositions;
        GpuMesh gm;
        gm.meshIndex = int(i);
        gm.shapeVersion = mesh.shapeVersion;
        gm.flags = mesh.flags;
        gm.indexCount = GLsizei(mesh.triangles.size() * 3);
        place(gm, mesh);
        gm.positions = gl::makeBuffer(positions.data(), positions.size() * sizeof(glm::vec3));
        gm.indices = gl::makeBuffer(mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
        gm.clusters = clustersOf(mesh);
        std::vector<glm::vec4> normals = faceNormalBuffer(mesh);
        gm.faceNormals = gl::makeBuffer(normals.data(), normals.size() * sizeof(glm::vec4));
        GLuint vao = 0;
        g.CreateVertexArrays(1, &vao);
        gm.vao = gl::VertexArrayHandle(vao);
        g.VertexArrayVertexBuffer(vao, 0, gm.positions.id(), 0, sizeof(glm::vec3));
        g.VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
        g.VertexArrayAttribBinding(vao, 0, 0);
        g.EnableVertexArrayAttrib(vao, 0);
        g.VertexArrayElementBuffer(vao, gm.indices.id());
        if (mesh.alpha)
            gm.seeThrough = std::make_shared<const GpuSeeThrough>(uploadSeeThrough(*mesh.alpha, mesh.triangles.size()));
        meshes_.push_back(std::move(gm));
        ++stats_.meshUploads;
    }
    g.check("uploading the scene meshes");
    g.Finish();
    stats_.uploadMs += msSince(start);
    meshesGeometryVersion_ = scene_->geometryVersion();
    return meshes_;
}

void SceneCache::drawMeshes(const gl::Program& program, uint32_t requiredFlags,
                       const std::function<void(const GpuMesh&)>& before) {
    drawMeshesWhere(program, requiredFlags, std::nullopt, before);
}

namespace {

// Sets the uniforms of "common/mesh_placement.glsl" for mesh `m`.
void setPlacement(const gl::Program& program, const GpuMesh& m) {
    program.set("uTransformed", m.transformed ? 1 : 0);
    program.set("uObjectToWorld", m.objectToWorld);
    program.set("uNormalToWorld", m.normalToWorld);
}

// Whether the box (object space, placed by `m`) may cover a pixel of the region's rectangle; a
// box reaching behind the eye may cover anything.
bool reaches(const PatchRegion& region, const GpuMesh& m, const Bounds& objectBox) {
    Bounds world = objectBox;
    if (m.transformed) {
        world = Bounds{};
        for (const glm::vec3& corner : objectBox.corners()) world.extend(glm::vec3(m.objectToWorld * glm::vec4(corner, 1.0f)));
    }
    std::optional<PixelRect> r = boxesOnScreen({world}, region.worldToClip, region.width, region.height);
    const PixelRect& rect = region.rect;
    return !r || (r->x0 < rect.x1 && rect.x0 < r->x1 && r->y0 < rect.y1 && rect.y0 < r->y1);
}

}  // namespace

void SceneCache::drawMeshesWhere(const gl::Program& program, uint32_t requiredFlags,
                            const std::optional<PatchRegion>& region,
                            const std::function<void(const GpuMesh&)>& before, int castingFor,
                            bool skipSeeThrough) {
    const gl::Functions& g = gl();
    auto draw = [&](uint32_t firstTriangle, uint32_t triangles) {
        if (region) stats_.patchTriangles += triangles;
        g.DrawElements(GL_TRIANGLES, GLsizei(3 * triangles), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(size_t(firstTriangle) * 3 * sizeof(uint32_t)));
    };
    for (const GpuMesh& m : meshes()) {
        if ((m.flags & requiredFlags) != requiredFlags || m.indexCount == 0) continue;
        if (skipSeeThrough && m.seeThrough) continue;
        if (castingFor >= 0 && !scene_->castsFor(m.meshIndex, castingFor)) continue;
        setPlacement(program, m);
        if (before) before(m);
        g.BindVertexArray(m.vao.id());
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m.faceNormals.id());
        if (!region) {
            draw(0, uint32_t(m.indexCount / 3));
            continue;
        }
        // Consecutive clusters that reach the rectangle go in one draw.
        uint32_t runFirst = 0, runTriangles = 0;
        for (const GpuMesh::Cluster& c : m.clusters) {
            if (reaches(*region, m, c.bounds)) {
                if (runTriangles == 0) runFirst = c.firstTriangle;
                runTriangles += c.triangleCount;
            } else if (runTriangles > 0) {
                draw(runFirst, runTriangles);
                runTriangles = 0;
            }
        }
        if (runTriangles > 0) draw(runFirst, runTriangles);
    }
    g.BindVertexArray(0);
}

void SceneCache::drawSeeThroughWhere(const gl::Program& program, uint32_t requiredFlags,
                                const std::function<void(const GpuMesh&)>& before, int castingFor) {
    const gl::Functions& g = gl();
    bool bound = false;
    for (const GpuMesh& m : meshes()) {
        if ((m.flags & requiredFlags) != requiredFlags || m.indexCount == 0 || !m.seeThrough) continue;
        if (castingFor >= 0 && !scene_->castsFor(m.meshIndex, castingFor)) continue;
        if (!bound) bindEmptyVertexArray(), bound = true;
        setPlacement(program, m);
        if (before) before(m);
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m.faceNormals.id());
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m.indices.id());
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m.positions.id());
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m.seeThrough->cornerUvs.id());
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, m.seeThrough->triangleMaterial.id());
        for (size_t k = 0; k < m.seeThrough->materials.size(); ++k) {
            const GpuSeeThrough::Material& mat = m.seeThrough->materials[k];
            if (!mat.textured && !(mat.constant > 0.0f)) continue;  // lets everything through
            program.set("uAlphaMaterial", uint32_t(k));
            program.set("uAlphaTextured", mat.textured ? 1 : 0);
            program.set("uAlphaConstant", mat.constant);
            if (mat.textured) program.setTexture("uAlphaTexture", kAlphaTextureUnit, mat.texture.id());
            g.DrawArrays(GL_TRIANGLES, 0, m.indexCount);
        }
    }
    if (bound) g.BindVertexArray(0);
}

void SceneCache::bindEmptyVertexArray() {
    if (!emptyVao_) {
        GLuint vao = 0;
        gl().CreateVertexArrays(1, &vao);
        emptyVao_ = gl::VertexArrayHandle(vao);
    }
    gl().BindVertexArray(emptyVao_.id());
}

void SceneCache::drawFullscreen() {
    const gl::Functions& g = gl();
    bindEmptyVertexArray();
    g.DrawArrays(GL_TRIANGLES, 0, 3);
    g.BindVertexArray(0);
}

namespace {

// Confines what follows to `rect` (clears included) when there is one.
void scissor(const gl::Functions& g, const std::optional<PixelRect>& rect) {
    if (!rect) return;
    g.Enable(GL_SCISSOR_TEST);
    g.Scissor(rect->x0, rect->y0, rect->x1 - rect->x0, rect->y1 - rect->y0);
}

// The region a patch of a width x height pass redraws: nothing without a rectangle (a whole pass).
std::optional<PatchRegion> patchRegion(const std::optional<PixelRect>& rect, const glm::mat4& worldToClip,
                                              int width, int height) {
    if (!rect) return std::nullopt;
    return PatchRegion{*rect, worldToClip, width, height};
}

}  // namespace

void SceneCache::listCoveringTriangles(const Camera& camera, const PixelRect& rect) {
    // The runs of triangles to test: per mesh, its consecutive clusters that reach the rectangle.
    struct Run {
        size_t mesh;
        uint32_t first, count;
        size_t start;  // in the sequence of tested triangles
    };
    const PatchRegion region{rect, camera.worldToClip(), camera.width, camera.height};
    meshes();
    std::vector<Run> runs;
    size_t tested = 0;
    for (size_t i = 0; i < meshes_.size(); ++i) {
        const GpuMesh& m = meshes_[i];
        if (m.indexCount == 0) continue;
        for (const GpuMesh::Cluster& c : m.clusters) {
            if (!reaches(region, m, c.bounds)) continue;
            if (!runs.empty() && runs.back().mesh == i && runs.back().first + runs.back().count == c.firstTriangle)
                runs.back().count += c.triangleCount;
            else
                runs.push_back(Run{i, c.firstTriangle, c.triangleCount, tested});
            tested += c.triangleCount;
        }
    }
    // Two halves of the sequence, each with its own scratch: listed_[0] then listed_[1] is the
    // list in order, mesh after mesh.
    std::vector<size_t> perMesh[2] = {std::vector<size_t>(meshes_.size(), 0), std::vector<size_t>(meshes_.size(), 0)};
    listed_[0].clear();
    listed_[1].clear();
    if (culling_ == CameraCulling::Auto) {
        const GLubyte* name = gl().GetString(GL_RENDERER);
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
        size_t mesh = meshes_.size();
        for (const Run& run : runs) {
            const size_t from = std::max(begin, run.start), to = std::min(end, run.start + run.count);
            if (from >= to) continue;
            const GpuMesh& m = meshes_[run.mesh];
            const Mesh& sceneMesh = scene_->meshes()[size_t(m.meshIndex)];
            if (run.mesh != mesh) {
                coverage_[part].beginMesh(CoverageView{camera.worldToClip(), m.transformed, m.objectToWorld,
                                                       camera.width, camera.height, rect},
                                          sceneMesh.objectPositions);
                mesh = run.mesh;
            }
            const size_t before = out.size();
            coverage_[part].append(sceneMesh.triangles, run.first + uint32_t(from - run.start), uint32_t(to - from), out);
            perMesh[part][run.mesh] += out.size() - before;
        }
    };
    if (culling_ == CameraCulling::EachTriangle) splitTwo(tested, testEach);
    listedRanges_.clear();
    size_t first = 0;
    for (size_t i = 0; i < meshes_.size(); ++i) {
        const size_t count = perMesh[0][i] + perMesh[1][i];
        listedRanges_.emplace_back(first, count);
        first += count;
    }
}

void SceneCache::drawCameraPass(CameraPass& pass, const std::optional<PixelRect>& rect) {
    const gl::Functions& g = gl();
    const Camera& cam = camera();
    listCoveringTriangles(cam, rect ? *rect : PixelRect{0, 0, pass.width, pass.height});
    const size_t listed = listed_[0].size() + listed_[1].size();
    stats_.cameraPassTriangles += listed;
    if (rect) stats_.patchTriangles += listed;
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
    scissor(g, rect);
    fb.clearColor(0, glm::vec4(0.0f));
    fb.clearColor(1, glm::vec4(0.0f));
    fb.clearColor(2, glm::vec4(-1.0f, -1.0f, 0.0f, 0.0f));
    fb.clearDepth(1.0f);
    gl::apply(gl::states::opaque);

    // Meshes the camera may see through (a cut-out's holes) are drawn with the alpha-tested
    // variant, one material at a time as drawSeeThroughWhere draws them.
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
    bindEmptyVertexArray();
    if (listed > 0) g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, listedBuffer_.id());
    for (size_t i = 0; i < meshes_.size(); ++i) {
        const auto [first, count] = listedRanges_[i];
        if (count == 0) continue;
        const GpuMesh& m = meshes_[i];
        if (m.flags & SS_MESH_CAMERA_HIDDEN) continue;  // the camera sees past it
        const bool alphaTested = m.seeThrough && m.seeThrough->cameraSeesThrough;
        const gl::Program& prog = alphaTested ? seeThrough : opaque;
        if (&prog != inUse) prog.use(), inUse = &prog;
        setPlacement(prog, m);
        prog.set("uMeshIndex", m.meshIndex);
        prog.set("uReceives", m.receives() ? 1.0f : 0.0f);
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m.faceNormals.id());
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m.indices.id());
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m.positions.id());
        if (!alphaTested) {
            g.DrawArrays(GL_TRIANGLES, GLint(3 * first), GLsizei(3 * count));
            continue;
        }
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m.seeThrough->cornerUvs.id());
        g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, m.seeThrough->triangleMaterial.id());
        for (size_t k = 0; k < m.seeThrough->materials.size(); ++k) {
            const GpuSeeThrough::Material& mat = m.seeThrough->materials[k];
            if (!mat.textured && mat.constant < kCameraAlphaThreshold) continue;  // the camera sees past it
            prog.set("uAlphaMaterial", uint32_t(k));
            prog.set("uAlphaTextured", mat.textured ? 1 : 0);
            prog.set("uAlphaConstant", mat.constant);
            if (mat.textured) prog.setTexture("uAlphaTexture", kAlphaTextureUnit, mat.texture.id());
            g.DrawArrays(GL_TRIANGLES, GLint(3 * first), GLsizei(3 * count));
        }
    }
    g.BindVertexArray(0);
    g.Disable(GL_SCISSOR_TEST);
    g.BindFramebuffer(GL_FRAMEBUFFER, 0);
    g.check("drawing the camera pass");
}

const CameraPass& SceneCache::cameraPass() {
    dropStalePasses();
    if (camera_ && cameraPassGeometry_ == scene_->geometryVersion()) return *camera_;
    meshes();  // uploads timed apart
    const auto start = Clock::now();
    std::vector<MeshPlacement> now = placements();
    if (camera_) {
        // Only moves since it was drawn: redrawn where the moved meshes were and are.
        std::optional<std::vector<Bounds>> moved = movedBoxes(cameraPlacements_, now);
        std::optional<PixelRect> rect;
        if (moved) rect = boxesOnScreen(*moved, camera().worldToClip(), camera_->width, camera_->height);
        if (rect) {
            if (!rect->empty()) drawCameraPass(*camera_, rect);
            ++stats_.cameraPassesPatched;
        } else {
            drawCameraPass(*camera_, std::nullopt);
        }
    } else {
        const Camera& cam = camera();
        auto pass = std::make_unique<CameraPass>();
        pass->width = cam.width;
        pass->height = cam.height;
        pass->framebuffer = gl::Framebuffer(cam.width, cam.height, {GL_RGBA32F, GL_RGBA32F, GL_RG32F},
                                            GL_DEPTH_COMPONENT32F);
        drawCameraPass(*pass, std::nullopt);
        camera_ = std::move(pass);
    }
    gl().Finish();
    receiversInView_.reset();
    stats_.cameraPassMs += msSince(start);
    ++stats_.cameraPasses;
    cameraPlacements_ = std::move(now);
    cameraPassCamera_ = scene_->cameraVersion();
    cameraPassGeometry_ = scene_->geometryVersion();
    return *camera_;
}

const CameraImages& SceneCache::cameraImages() {
    dropStalePasses();
    if (cameraImages_) return *cameraImages_;
    const CameraPass& pass = cameraPass();
    auto img = std::make_unique<CameraImages>();
    img->width = pass.width;
    img->height = pass.height;
    img->positionDepth = pass.framebuffer.readRgba(0);
    img->normalReceive = pass.framebuffer.readRgba(1);
    img->ids = pass.framebuffer.readRgba(2);
    ++stats_.cameraReadbacks;
    cameraImages_ = std::move(img);
    return *cameraImages_;
}

void SceneCache::drawShadowMap(ShadowMap& map, int lightIndex, const std::optional<PixelRect>& rect) {
    const gl::Functions& g = gl();
    gl::Framebuffer fb(map.size, map.size, {});
    fb.attachColor(0, map.distance.id());
    fb.attachDepth(map.depth.id());
    fb.bind();
    scissor(g, rect);
    fb.clearColor(0, glm::vec4(ShadowMap::kEmpty));
    fb.clearDepth(1.0f);
    // Casters nearer the light than the near plane (beyond the fit box, towards the light)
    // still shadow: clamped onto it, they keep their true distance.
    gl::apply(gl::states::opaqueDepthClamped);
    const gl::Program& prog = gl::program("common/mesh.vert.glsl", "shadow_map/distance.frag.glsl");
    prog.use();
    prog.set("uWorldToClip", map.worldToClip());
    bindShadowMapUniforms(prog, map);
    drawMeshesWhere(prog, SS_MESH_CAST, patchRegion(rect, map.worldToClip(), map.size, map.size), {}, lightIndex, true);
    // See-through casters are alpha-tested (hashed): drawn whole, also in a patch (the scissor
    // keeps the rest of the map).
    const gl::Program& seeThrough = gl::program("shadow_map/see_through.vert.glsl", "shadow_map/see_through.frag.glsl");
    seeThrough.use();
    seeThrough.set("uWorldToClip", map.worldToClip());
    bindShadowMapUniforms(seeThrough, map);
    drawSeeThroughWhere(seeThrough, SS_MESH_CAST, {}, lightIndex);
    g.Disable(GL_SCISSOR_TEST);
    g.BindFramebuffer(GL_FRAMEBUFFER, 0);
    g.check("drawing a shadow map");
}

const ShadowMap& SceneCache::shadowMap(int lightIndex, int size) {
    if (size <= 0) size = kDefaultShadowMapSize;
    const Bounds fit = shadowFitBounds(lightIndex);  // drops the stale passes
    auto key = std::make_pair(light(lightIndex).version, size);
    auto it = shadowMaps_.find(key);
    if (it != shadowMaps_.end() && !(it->second.fit.lo == fit.lo && it->second.fit.hi == fit.hi)) {
        // Fit around what the camera sees, and that moved: drawn afresh.
        stats_.shadowMapBytes -= it->second.bytes;
        shadowMaps_.erase(it);
        it = shadowMaps_.end();
    }
    if (it != shadowMaps_.end()) {
        CachedShadowMap& entry = it->second;
        entry.lastUse = ++useClock_;
        if (!entry.pending.empty()) {
            // Moves since it was drawn (the fit is the same: dropStalePasses checked the bounds).
            meshes();
            const auto start = Clock::now();
            ShadowMap& map = *entry.map;
            std::optional<PixelRect> rect = boxesOnScreen(entry.pending, map.worldToClip(), map.size, map.size);
            if (!rect || !rect->empty()) drawShadowMap(map, lightIndex, rect);
            if (rect) ++stats_.shadowMapsPatched;
            entry.pending.clear();
            gl().Finish();
            stats_.shadowMapMs += msSince(start);
            ++stats_.shadowMaps;
        }
        return *entry.map;
    }
    const Light& L = light(lightIndex);
    meshes();  // uploads timed apart
    const auto start = Clock::now();
    auto map = std::make_unique<ShadowMap>(fitShadowMap(L, fit, size));
    map->distance = gl::Texture(size, size, GL_R32F, GL_NEAREST);
    map->depth = gl::Texture(size, size, GL_DEPTH_COMPONENT32F, GL_NEAREST);
    drawShadowMap(*map, lightIndex, std::nullopt);
    gl().Finish();
    stats_.shadowMapMs += msSince(start);
    ++stats_.shadowMaps;
    CachedShadowMap entry;
    entry.map = std::move(map);
    entry.lastUse = ++useClock_;
    entry.fit = fit;
    entry.bytes = size_t(size) * size_t(size) * (sizeof(float) + sizeof(float));  // R32F + depth 32F
    stats_.shadowMapBytes += entry.bytes;
    stats_.shadowMapBytesPeak = std::max(stats_.shadowMapBytesPeak, stats_.shadowMapBytes);
    return *shadowMaps_.emplace(key, std::move(entry)).first->second.map;
}

void SceneCache::dropStale() {
    dropStalePasses();
    traceScenes_.dropStale(*scene_);
    // Maps of lights edited or removed since are never asked for again.
    for (auto it = shadowMaps_.begin(); it != shadowMaps_.end();) {
        bool current = false;
        for (const Light& l : scene_->lights()) current = current || l.version == it->first.first;
        if (current) {
            ++it;
        } else {
            stats_.shadowMapBytes -= it->second.bytes;
            it = shadowMaps_.erase(it);
        }
    }
}

void SceneCache::trimCameraImages(size_t keepBytes) {
    if (cameraImages_ && size_t(cameraImages_->width) * size_t(cameraImages_->height) * 3 * sizeof(glm::vec4) > keepBytes)
        cameraImages_.reset();
}

void SceneCache::trimCache(size_t budgetBytes) {
    while (stats_.shadowMapBytes > budgetBytes && !shadowMaps_.empty()) {
        auto oldest = shadowMaps_.begin();
        for (auto it = shadowMaps_.begin(); it != shadowMaps_.end(); ++it)
            if (it->second.lastUse < oldest->second.lastUse) oldest = it;
        stats_.shadowMapBytes -= oldest->second.bytes;
        ++stats_.shadowMapsEvicted;
        shadowMaps_.erase(oldest);
    }
}

void SceneCache::bindShadowMapUniforms(const gl::Program& program, const ShadowMap& map) const {
    program.set("uShadowWorldToClip", map.worldToClip());
    program.set("uShadowOrigin", map.origin);
    program.set("uShadowAxis", map.axis);
    program.set("uShadowOrthographic", map.orthographic ? 1 : 0);
    program.set("uShadowSize", float(map.size));
    program.set("uShadowTexelScale",
                map.orthographic ? 2.0f * map.halfWidth / float(map.size) : 2.0f * map.tanHalfFov / float(map.size));
}

int SceneCache::bindShadowMap(const gl::Program& program, const ShadowMap& map, int unit) const {
    program.setTexture("uShadowDistance", unit, map.distance.id());
    bindShadowMapUniforms(program, map);
    return unit + 1;
}

int SceneCache::bindCameraPass(const gl::Program& program, int firstUnit) {
    const CameraPass& pass = cameraPass();
    program.setTexture("uCamPositionDepth", firstUnit, pass.positionDepth());
    program.setTexture("uCamNormalReceive", firstUnit + 1, pass.normalReceive());
    program.setTexture("uCamIds", firstUnit + 2, pass.ids());
    return firstUnit + 3;
}

void SceneCache::setLightUniforms(const gl::Program& program, int lightIndex) const {
    const Light& L = light(lightIndex);
    program.set("uLight.type", int(L.type));
    program.set("uLight.position", L.position());
    program.set("uLight.direction", L.direction());
    program.set("uLight.halfAxisX", L.isArea() ? L.halfAxisX() : glm::vec3(0.0f));
    program.set("uLight.halfAxisY", L.isArea() ? L.halfAxisY() : glm::vec3(0.0f));
    program.set("uLight.radius", L.radius);
    program.set("uLight.equivalentRadius", L.equivalentRadius());
    program.set("uLight.cosHalfSpot", std::cos(0.5f * L.spotSize));
    program.set("uLight.sinHalfSun", std::sin(L.sunHalfAngle()));
}

}  // namespace ss
