// How the scene's meshes are drawn, whole or culled to a patch's rectangle cluster by cluster.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/mesh_draws.h"

#include "scene_cache/shader_uniforms.h"

namespace ss {

void EmptyVertexArray::bind() {
    const gl::Functions& g = gl::api();
    if (!vao_) {
        GLuint vao = 0;
        g.CreateVertexArrays(1, &vao);
        vao_ = gl::VertexArrayHandle(vao);
    }
    g.BindVertexArray(vao_.id());
}

bool reachesRegion(const PatchRegion& region, const GpuMesh& m, const Bounds& objectBox) {
    Bounds world = objectBox;
    if (m.transformed) {
        world = Bounds{};
        for (const glm::vec3& corner : objectBox.corners())
            world.extend(glm::vec3(m.objectToWorld * glm::vec4(corner, 1.0f)));
    }
    std::optional<PixelRect> r = boxesOnScreen({world}, region.worldToClip, region.width, region.height);
    const PixelRect& rect = region.rect;
    return !r || (r->x0 < rect.x1 && rect.x0 < r->x1 && r->y0 < rect.y1 && rect.y0 < r->y1);
}

std::optional<PatchRegion> patchRegion(const std::optional<PixelRect>& rect, const glm::mat4& worldToClip,
                                       int width, int height) {
    if (!rect) return std::nullopt;
    return PatchRegion{*rect, worldToClip, width, height};
}

void scissorTo(const gl::Functions& g, const std::optional<PixelRect>& rect) {
    if (!rect) return;
    g.Enable(GL_SCISSOR_TEST);
    g.Scissor(rect->x0, rect->y0, rect->x1 - rect->x0, rect->y1 - rect->y0);
}

void MeshDraws::drawWhere(const gl::Program& program, uint32_t requiredFlags,
                          const std::optional<PatchRegion>& region,
                          const std::function<void(const GpuMesh&)>& before, int castingFor,
                          bool skipSeeThrough) const {
    const gl::Functions& g = gl::api();
    auto draw = [&](uint32_t firstTriangle, uint32_t triangles) {
        if (region) stats.patchTriangles += triangles;
        g.DrawElements(GL_TRIANGLES, GLsizei(3 * triangles), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(size_t(firstTriangle) * 3 * sizeof(uint32_t)));
    };
    for (const GpuMesh& m : meshes) {
        if ((m.flags & requiredFlags) != requiredFlags || m.indexCount == 0) continue;
        if (skipSeeThrough && m.seeThrough) continue;
        if (castingFor >= 0 && !scene.castsFor(m.meshIndex, castingFor)) continue;
        setPlacementUniforms(program, m);
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
            if (reachesRegion(*region, m, c.bounds)) {
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

void MeshDraws::drawSeeThroughWhere(const gl::Program& program, uint32_t requiredFlags,
                                    const std::function<void(const GpuMesh&)>& before, int castingFor) const {
    const gl::Functions& g = gl::api();
    bool bound = false;
    for (const GpuMesh& m : meshes) {
        if ((m.flags & requiredFlags) != requiredFlags || m.indexCount == 0 || !m.seeThrough) continue;
        if (castingFor >= 0 && !scene.castsFor(m.meshIndex, castingFor)) continue;
        if (!bound) emptyVertexArray.bind(), bound = true;
        setPlacementUniforms(program, m);
        if (before) before(m);
        bindMeshStorage(g, m);
        for (size_t k = 0; k < m.seeThrough->materials.size(); ++k) {
            const GpuSeeThrough::Material& mat = m.seeThrough->materials[k];
            if (!mat.textured && !(mat.constant > 0.0f)) continue;  // lets everything through
            setAlphaMaterialUniforms(program, mat, uint32_t(k));
            g.DrawArrays(GL_TRIANGLES, 0, m.indexCount);
        }
    }
    if (bound) g.BindVertexArray(0);
}

}  // namespace ss
