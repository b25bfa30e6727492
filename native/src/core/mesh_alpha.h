// What a mesh's materials let through on shadow rays: per-triangle material, per-corner UVs and,
// per material, a constant alpha or an alpha texture (the Cycles contract: transmission 1 - alpha).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ss {

// Where a camera ray meets a see-through surface it stops when the alpha there is at least this
// and passes on otherwise (the GL camera pass's alpha test and the reference's camera rays alike).
// Cycles blends a fractional alpha into the pixel; a pass shows one surface per pixel, so a
// pixel of a cut-out is the card or what lies behind its hole, and a 50 % card is seen.
inline constexpr float kCameraAlphaThreshold = 0.5f;

enum class AlphaWrap : int32_t { Repeat = 0, Extend = 1, Clip = 2 };  // Blender's image extension
enum class AlphaFilter : int32_t { Linear = 0, Closest = 1 };          // Blender's interpolation

// One material's alpha: `constant` where it has no texture, else the texture sampled at the UV.
struct AlphaMaterial {
    float constant = 1.0f;
    int width = 0, height = 0;
    std::vector<float> texels;  // width * height alphas, row 0 at v = 0 (Blender's image.pixels)
    AlphaWrap wrap = AlphaWrap::Repeat;
    AlphaFilter filter = AlphaFilter::Linear;

    bool textured() const { return !texels.empty(); }
    // Alpha in [0, 1] at `uv` (texel centres at (i + 0.5) / width, as Cycles samples images).
    float alphaAt(glm::vec2 uv) const;
    // Alpha is 1 everywhere: the material is opaque.
    bool opaque() const;
};

struct MeshAlpha {
    std::vector<glm::vec2> cornerUvs;         // 3 per triangle (empty: every UV is (0, 0))
    std::vector<uint32_t> triangleMaterial;   // 1 per triangle (empty: material 0 everywhere)
    std::vector<AlphaMaterial> materials;     // at least one

    // Throws ss::Error (SS_ERROR_INVALID_SCENE) naming mesh `meshName` when the arrays do not fit
    // `triangleCount` triangles, a material index is out of range or an alpha is not in [0, 1].
    void validate(const std::string& meshName, size_t triangleCount) const;
    // Every material is opaque: the mesh blocks like one without materials.
    bool opaque() const;
    const AlphaMaterial& materialOf(uint32_t triangle) const {
        return materials[triangleMaterial.empty() ? 0u : triangleMaterial[triangle]];
    }
    // Alpha at the point of `triangle` with barycentric weights b1, b2 of its corners 1 and 2
    // (Embree's u, v).
    float alpha(uint32_t triangle, float b1, float b2) const;
    // 1 - alpha there: what a shadow ray lets through.
    float transmission(uint32_t triangle, float b1, float b2) const { return 1.0f - alpha(triangle, b1, b2); }
    // Whether a camera ray stops there (kCameraAlphaThreshold).
    bool seenByCamera(uint32_t triangle, float b1, float b2) const {
        return alpha(triangle, b1, b2) >= kCameraAlphaThreshold;
    }
    // Some point of the mesh lets a camera ray through (a material below kCameraAlphaThreshold
    // somewhere).
    bool cameraSeesThrough() const;
};

}  // namespace ss
