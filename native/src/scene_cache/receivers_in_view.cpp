// What the camera sees that can receive a shadow: the bounds the shadow maps are fit around.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>

#include "scene_cache/camera_pass.h"

namespace ss {

const Bounds& CameraPassCache::receiversInView(const MeshDraws& draws) {
    const CameraPass& pass = get(draws);
    if (receiversInView_) return *receiversInView_;
    // A band of rows at a time (about 16 MiB for each of the two attachments), so an 8192² pass
    // is never held twice on the CPU.
    const int band = std::max(1, int((size_t(16) << 20) / (sizeof(glm::vec4) * size_t(pass.width))));
    Bounds b;
    for (int y = 0; y < pass.height; y += band) {
        const int rows = std::min(band, pass.height - y);
        const std::vector<glm::vec4> position = pass.framebuffer.readRgbaRows(0, y, rows);
        const std::vector<glm::vec4> normal = pass.framebuffer.readRgbaRows(1, y, rows);
        for (size_t i = 0; i < position.size(); ++i)
            if (position[i].w > 0.0f && normal[i].w > 0.5f && std::isfinite(position[i].x) &&
                std::isfinite(position[i].y) && std::isfinite(position[i].z))
                b.extend(glm::vec3(position[i]));
    }
    receiversInView_ = b;
    return *receiversInView_;
}

}  // namespace ss
