// How the C API hands out the sweep method's shadow mesh (world-space vertices with intensity).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstring>
#include <unordered_map>
#include <vector>

#include "capi/capi_internal.h"
#include "methods/method.h"
#include "methods/sweep/shadow.h"
#include "renderer/render_memory.h"

struct ss_sweep_mesh {
    std::vector<float> xyz, intensity;
    std::vector<uint32_t> triangles;
    int32_t receiver = -1, samplesUsed = 0;
};

namespace {

struct VertexKey {
    double x, y;
    float intensity;
    bool operator==(const VertexKey& o) const {
        return std::memcmp(this, &o, sizeof(double) * 2) == 0 && intensity == o.intensity;
    }
};
struct VertexKeyHash {
    size_t operator()(const VertexKey& k) const {
        uint64_t a, b;
        std::memcpy(&a, &k.x, 8);
        std::memcpy(&b, &k.y, 8);
        return size_t(a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull) ^ uint64_t(k.intensity * 65536.0f));
    }
};

}  // namespace

extern "C" {

SS_API ss_status ss_sweep_shadow_mesh(const ss_scene* scene, int32_t light_index,
                                      const ss_render_options* options, ss_sweep_mesh** out) {
    return ss::capi::guarded([&] {
        ss::capi::require(scene, "ss_sweep_shadow_mesh", "scene");
        ss::capi::require(out, "ss_sweep_shadow_mesh", "out");
        *out = nullptr;
        ss::RenderSettings settings = ss::capi::renderSettingsFrom(options, "ss_sweep_shadow_mesh", nullptr);
        ss::takeMemoryLimit(settings);  // the mesh is refused past it before its weights are made
        settings.requireKnownKeys("sweep", ss::sweepSettings());
        settings.report(0.0f, "sweep: shadow mesh");
        ss::SweepShadow shadow = ss::computeSweepShadow(scene->scene, light_index, ss::sweepOptions(settings));
        settings.report(1.0f, "sweep: done");
        auto mesh = std::make_unique<ss_sweep_mesh>();
        mesh->receiver = shadow.plane.mesh;
        mesh->samplesUsed = shadow.samplesUsed;
        // The fill emits each triangle's corners separately; shared corners with the same
        // intensity become one vertex.
        std::unordered_map<VertexKey, uint32_t, VertexKeyHash> index;
        for (size_t i = 0; i < shadow.mesh.indices.size(); ++i) {
            const auto& v = shadow.mesh.vertices[shadow.mesh.indices[i]];
            VertexKey k{v.x, v.y, v.intensity};
            auto [it, inserted] = index.emplace(k, uint32_t(mesh->intensity.size()));
            if (inserted) {
                glm::dvec3 w = shadow.worldVertex(shadow.mesh.indices[i]);
                mesh->xyz.insert(mesh->xyz.end(), {float(w.x), float(w.y), float(w.z)});
                mesh->intensity.push_back(v.intensity);
            }
            mesh->triangles.push_back(it->second);
        }
        *out = mesh.release();
    });
}

SS_API void ss_sweep_mesh_destroy(ss_sweep_mesh* mesh) { delete mesh; }

SS_API ss_status ss_sweep_mesh_data(const ss_sweep_mesh* mesh, const float** xyz, const float** intensity,
                                    uint32_t* vertex_count, const uint32_t** triangles, uint32_t* triangle_count) {
    return ss::capi::guarded([&] {
        ss::capi::require(mesh, "ss_sweep_mesh_data", "mesh");
        if (xyz) *xyz = mesh->xyz.data();
        if (intensity) *intensity = mesh->intensity.data();
        if (vertex_count) *vertex_count = uint32_t(mesh->intensity.size());
        if (triangles) *triangles = mesh->triangles.data();
        if (triangle_count) *triangle_count = uint32_t(mesh->triangles.size() / 3);
    });
}

SS_API ss_status ss_sweep_mesh_info(const ss_sweep_mesh* mesh, int32_t* receiver_mesh, int32_t* samples_used) {
    return ss::capi::guarded([&] {
        ss::capi::require(mesh, "ss_sweep_mesh_info", "mesh");
        if (receiver_mesh) *receiver_mesh = mesh->receiver;
        if (samples_used) *samples_used = mesh->samplesUsed;
    });
}

}  // extern "C"
