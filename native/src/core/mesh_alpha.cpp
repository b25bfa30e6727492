// How a material's alpha is looked up at a point of a triangle.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/mesh_alpha.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace ss {
namespace {

// The texel index along one axis for wrap mode `wrap`; -1 where Clip leaves the image.
int wrapIndex(int i, int n, AlphaWrap wrap) {
    switch (wrap) {
    case AlphaWrap::Repeat: return ((i % n) + n) % n;
    case AlphaWrap::Extend: return std::clamp(i, 0, n - 1);
    case AlphaWrap::Clip: return i < 0 || i >= n ? -1 : i;
    }
    return -1;
}

bool unitInterval(float a) { return std::isfinite(a) && a >= 0.0f && a <= 1.0f; }

}  // namespace

float AlphaMaterial::alphaAt(glm::vec2 uv) const {
    if (!textured()) return constant;
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return 1.0f;
    auto texel = [&](int x, int y) {
        const int wx = wrapIndex(x, width, wrap), wy = wrapIndex(y, height, wrap);
        return wx < 0 || wy < 0 ? 0.0f : texels[size_t(wy) * size_t(width) + size_t(wx)];
    };
    // Far from the image, Repeat keeps only the fraction (float index arithmetic stays exact).
    if (wrap == AlphaWrap::Repeat) uv -= glm::floor(uv);
    const float fx = uv.x * float(width) - 0.5f, fy = uv.y * float(height) - 0.5f;
    if (filter == AlphaFilter::Closest) {
        if (wrap == AlphaWrap::Clip && (uv.x < 0.0f || uv.x > 1.0f || uv.y < 0.0f || uv.y > 1.0f)) return 0.0f;
        return texel(int(std::floor(fx + 0.5f)), int(std::floor(fy + 0.5f)));
    }
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    const float tx = fx - x0, ty = fy - y0;
    const int ix = int(x0), iy = int(y0);
    const float a = texel(ix, iy) + tx * (texel(ix + 1, iy) - texel(ix, iy));
    const float b = texel(ix, iy + 1) + tx * (texel(ix + 1, iy + 1) - texel(ix, iy + 1));
    return std::clamp(a + ty * (b - a), 0.0f, 1.0f);
}

bool AlphaMaterial::opaque() const {
    if (!textured()) return constant >= 1.0f;
    if (wrap == AlphaWrap::Clip) return false;  // transparent outside the image
    return std::all_of(texels.begin(), texels.end(), [](float a) { return a >= 1.0f; });
}

void MeshAlpha::validate(const std::string& meshName, size_t triangleCount) const {
    const std::string where = "mesh '" + meshName + "' materials: ";
    if (materials.empty()) fail(SS_ERROR_INVALID_SCENE, where + "at least one material is needed");
    if (!cornerUvs.empty() && cornerUvs.size() != 3 * triangleCount)
        fail(SS_ERROR_INVALID_SCENE, where + std::to_string(cornerUvs.size()) + " corner UVs for " +
                                         std::to_string(triangleCount) + " triangles (3 per triangle)");
    for (const glm::vec2& uv : cornerUvs)
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) fail(SS_ERROR_INVALID_SCENE, where + "a UV is not finite");
    if (!triangleMaterial.empty() && triangleMaterial.size() != triangleCount)
        fail(SS_ERROR_INVALID_SCENE, where + std::to_string(triangleMaterial.size()) + " material indices for " +
                                         std::to_string(triangleCount) + " triangles");
    for (size_t t = 0; t < triangleMaterial.size(); ++t)
        if (triangleMaterial[t] >= materials.size())
            fail(SS_ERROR_INVALID_SCENE, where + "triangle " + std::to_string(t) + " has material " +
                                             std::to_string(triangleMaterial[t]) + " (there are " +
                                             std::to_string(materials.size()) + ")");
    for (size_t m = 0; m < materials.size(); ++m) {
        const AlphaMaterial& mat = materials[m];
        const std::string which = where + "material " + std::to_string(m) + ": ";
        if (!unitInterval(mat.constant)) fail(SS_ERROR_INVALID_SCENE, which + "alpha is not in [0, 1]");
        if (int32_t(mat.wrap) < 0 || int32_t(mat.wrap) > 2) fail(SS_ERROR_INVALID_SCENE, which + "unknown wrap mode");
        if (int32_t(mat.filter) < 0 || int32_t(mat.filter) > 1)
            fail(SS_ERROR_INVALID_SCENE, which + "unknown interpolation");
        if (!mat.textured()) continue;
        if (mat.width <= 0 || mat.height <= 0 || size_t(mat.width) * size_t(mat.height) != mat.texels.size())
            fail(SS_ERROR_INVALID_SCENE, which + "the texture has " + std::to_string(mat.texels.size()) +
                                             " texels, not width x height (" + std::to_string(mat.width) + " x " +
                                             std::to_string(mat.height) + ")");
        for (float a : mat.texels)
            if (!unitInterval(a)) fail(SS_ERROR_INVALID_SCENE, which + "a texel's alpha is not in [0, 1]");
    }
}

bool MeshAlpha::opaque() const {
    return std::all_of(materials.begin(), materials.end(), [](const AlphaMaterial& m) { return m.opaque(); });
}

bool MeshAlpha::cameraSeesThrough() const {
    return std::any_of(materials.begin(), materials.end(), [](const AlphaMaterial& m) {
        if (!m.textured()) return m.constant < kCameraAlphaThreshold;
        if (m.wrap == AlphaWrap::Clip) return true;  // transparent outside the image
        return std::any_of(m.texels.begin(), m.texels.end(), [](float a) { return a < kCameraAlphaThreshold; });
    });
}

float MeshAlpha::alpha(uint32_t triangle, float b1, float b2) const {
    const AlphaMaterial& m = materialOf(triangle);
    if (!m.textured()) return m.constant;
    glm::vec2 uv(0.0f);
    if (!cornerUvs.empty()) {
        const glm::vec2* c = &cornerUvs[3 * size_t(triangle)];
        uv = (1.0f - b1 - b2) * c[0] + b1 * c[1] + b2 * c[2];
    }
    return m.alphaAt(uv);
}

}  // namespace ss
