// Which part of a pass a move touched: the boxes moved meshes left and entered, on screen.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_cache/moved_region.h"

#include <algorithm>
#include <cmath>

namespace ss {

std::vector<MeshPlacement> placementsOf(const Scene& scene) {
    std::vector<MeshPlacement> out;
    for (const Mesh& m : scene.meshes()) {
        MeshPlacement p;
        p.shapeVersion = m.shapeVersion;
        p.objectToWorld = m.objectToWorld;
        for (const glm::vec3& v : m.positions) p.bounds.extend(v);
        out.push_back(p);
    }
    return out;
}

std::optional<std::vector<Bounds>> movedBoxes(const std::vector<MeshPlacement>& drawn,
                                              const std::vector<MeshPlacement>& now) {
    if (drawn.size() != now.size()) return std::nullopt;
    std::vector<Bounds> boxes;
    for (size_t i = 0; i < now.size(); ++i) {
        if (drawn[i].shapeVersion != now[i].shapeVersion) return std::nullopt;
        if (drawn[i].objectToWorld == now[i].objectToWorld) continue;
        if (!drawn[i].bounds.empty()) boxes.push_back(drawn[i].bounds);
        if (!now[i].bounds.empty()) boxes.push_back(now[i].bounds);
    }
    return boxes;
}

std::optional<PixelRect> boxesOnScreen(const std::vector<Bounds>& boxes, const glm::mat4& worldToClip, int width,
                                       int height) {
    // Two pixels beyond the projected corners: the GPU places the vertices with its own
    // float arithmetic (and the coverage rules round), never a pixel further.
    constexpr int kMargin = 2;
    PixelRect rect{width, height, 0, 0};
    for (const Bounds& b : boxes)
        for (const glm::vec3& c : b.corners()) {
            glm::vec4 clip = worldToClip * glm::vec4(c, 1.0f);
            if (!(clip.w > 1e-6f * (std::abs(clip.x) + std::abs(clip.y) + std::abs(clip.z)))) return std::nullopt;
            const float px = (clip.x / clip.w * 0.5f + 0.5f) * float(width);
            const float py = (clip.y / clip.w * 0.5f + 0.5f) * float(height);
            if (!std::isfinite(px) || !std::isfinite(py)) return std::nullopt;
            const float lo = -float(kMargin + 1), hiX = float(width + kMargin + 1), hiY = float(height + kMargin + 1);
            rect.x0 = std::min(rect.x0, int(std::floor(std::clamp(px, lo, hiX))) - kMargin);
            rect.y0 = std::min(rect.y0, int(std::floor(std::clamp(py, lo, hiY))) - kMargin);
            rect.x1 = std::max(rect.x1, int(std::ceil(std::clamp(px, lo, hiX))) + kMargin);
            rect.y1 = std::max(rect.y1, int(std::ceil(std::clamp(py, lo, hiY))) + kMargin);
        }
    rect.x0 = std::max(rect.x0, 0);
    rect.y0 = std::max(rect.y0, 0);
    rect.x1 = std::min(rect.x1, width);
    rect.y1 = std::min(rect.y1, height);
    return rect;
}

}  // namespace ss
