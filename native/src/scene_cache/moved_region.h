// Which part of a pass a move touched: what a pass drawn before some meshes moved must redraw.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace ss {

// Where each mesh was when a pass was drawn: a pass drawn with `drawn` needs redrawing only
// where the moved meshes were and are, as long as no mesh changed shape, came or went.
struct MeshPlacement {
    uint64_t shapeVersion = 0;
    glm::mat4 objectToWorld{1.0f};
    Bounds bounds;  // world
};

// A window rectangle of a pass (GL orientation: y up), half-open.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// What a patch of a width x height pass drawn with worldToClip redraws: the pixels of `rect`.
struct PatchRegion {
    PixelRect rect;
    glm::mat4 worldToClip{1.0f};
    int width = 0, height = 0;
};

// Where each of the scene's meshes is now (what a pass drawn now shows).
std::vector<MeshPlacement> placementsOf(const Scene& scene);
// The world boxes the moves from `drawn` to `now` touched (old and new place of each moved
// mesh), or nothing when more than moves happened (a mesh added, removed or reshaped).
std::optional<std::vector<Bounds>> movedBoxes(const std::vector<MeshPlacement>& drawn,
                                              const std::vector<MeshPlacement>& now);
// The pixels of a width x height pass drawn with `worldToClip` that the boxes may cover, grown
// by a margin for rasterisation; nothing when a box reaches behind the eye (redraw it all).
std::optional<PixelRect> boxesOnScreen(const std::vector<Bounds>& boxes, const glm::mat4& worldToClip, int width,
                                       int height);

}  // namespace ss
