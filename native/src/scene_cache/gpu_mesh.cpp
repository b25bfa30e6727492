// How the scene's meshes go to the GPU: buffers and clusters once per shape, placement per move.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/gpu_mesh.h"

#include <algorithm>
#include <map>

#include "core/stopwatch.h"

namespace ss {

bool GpuMesh::casts() const { return (flags & SS_MESH_CAST) != 0; }
bool GpuMesh::receives() const { return (flags & SS_MESH_RECEIVE) != 0; }

void bindMeshStorage(const gl::Functions& g, const GpuMesh& m) {
    g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m.faceNormals.id());
    g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m.indices.id());
    g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m.positions.id());
    if (!m.seeThrough) return;
    g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m.seeThrough->cornerUvs.id());
    g.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, m.seeThrough->triangleMaterial.id());
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
        c.triangleCount =
            uint32_t(std::min<size_t>(GpuMesh::kClusterTriangles, mesh.triangles.size() - first));
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

GpuMesh upload(const gl::Functions& g, const Mesh& mesh, int meshIndex) {
    const std::vector<glm::vec3>& positions = mesh.objectPositions;
    GpuMesh gm;
    gm.meshIndex = meshIndex;
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
        gm.seeThrough =
            std::make_shared<const GpuSeeThrough>(uploadSeeThrough(*mesh.alpha, mesh.triangles.size()));
    return gm;
}

}  // namespace

const std::vector<GpuMesh>& GpuMeshes::update(const Scene& scene, SceneCacheStats& stats) {
    if (geometryVersion_ == scene.geometryVersion()) return meshes_;
    const auto start = Clock::now();
    const gl::Functions& g = gl::api();
    const auto& src = scene.meshes();
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
        meshes_.push_back(upload(g, mesh, int(i)));
        ++stats.meshUploads;
    }
    g.check("uploading the scene meshes");
    g.Finish();
    stats.uploadMs += msSince(start);
    geometryVersion_ = scene.geometryVersion();
    return meshes_;
}

}  // namespace ss
