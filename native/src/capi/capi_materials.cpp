// How the C API hands a mesh its materials' alpha (what shadow rays see through).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "capi/capi_internal.h"

using namespace ss::capi;

extern "C" {

SS_API ss_status ss_scene_set_mesh_materials(ss_scene* scene, int32_t index, const float* corner_uvs,
                                             const int32_t* triangle_material,
                                             const ss_alpha_material* materials, int32_t material_count) {
    return guarded([&] {
        const char* fn = "ss_scene_set_mesh_materials";
        require(scene, fn, "scene");
        const ss::Mesh& mesh = scene->scene.mesh(index, fn);
        if (material_count < 0)
            ss::fail(SS_ERROR_INVALID_ARGUMENT, std::string(fn) + ": material_count is negative");
        if (material_count > 0) require(materials, fn, "materials");
        ss::MeshAlpha alpha;
        if (material_count == 0) {
            alpha.materials.resize(1);  // one opaque material: clears
            scene->scene.setMeshAlpha(index, std::move(alpha));
            return;
        }
        const size_t triangles = mesh.triangles.size();
        if (corner_uvs) {
            alpha.cornerUvs.resize(3 * triangles);
            for (size_t i = 0; i < alpha.cornerUvs.size(); ++i)
                alpha.cornerUvs[i] = glm::vec2(corner_uvs[2 * i], corner_uvs[2 * i + 1]);
        }
        if (triangle_material) {
            alpha.triangleMaterial.resize(triangles);
            for (size_t t = 0; t < triangles; ++t) {
                if (triangle_material[t] < 0 || triangle_material[t] >= material_count)
                    ss::fail(SS_ERROR_INVALID_SCENE, std::string(fn) + ": mesh '" + mesh.name + "' triangle " +
                                                         std::to_string(t) + " has material " +
                                                         std::to_string(triangle_material[t]) + " (there are " +
                                                         std::to_string(material_count) + ")");
                alpha.triangleMaterial[t] = uint32_t(triangle_material[t]);
            }
        }
        for (int32_t m = 0; m < material_count; ++m) {
            const ss_alpha_material& in = materials[m];
            ss::AlphaMaterial out;
            out.constant = in.alpha;
            out.wrap = ss::AlphaWrap(int32_t(in.wrap));
            out.filter = in.closest ? ss::AlphaFilter::Closest : ss::AlphaFilter::Linear;
            if (in.texture) {
                if (in.width <= 0 || in.height <= 0 || int64_t(in.width) * in.height > (int64_t(1) << 28))
                    ss::fail(SS_ERROR_INVALID_SCENE, std::string(fn) + ": mesh '" + mesh.name + "' material " +
                                                         std::to_string(m) + ": texture size " +
                                                         std::to_string(in.width) + " x " + std::to_string(in.height) +
                                                         " (1 .. 2^28 texels)");
                out.width = in.width;
                out.height = in.height;
                out.texels.assign(in.texture, in.texture + size_t(in.width) * size_t(in.height));
            }
            alpha.materials.push_back(std::move(out));
        }
        scene->scene.setMeshAlpha(index, std::move(alpha));
    });
}

}  // extern "C"
