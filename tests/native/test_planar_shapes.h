// Which small outlines the planar tests build their cases from.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <vector>

#include "planar/sweep_line.h"

namespace ss::planar::test {

// The clockwise outline of the rectangle [x0, x1] x [y0, y1], each edge of winding 1.
inline std::vector<DirectedEdge> rectEdges(int64_t x0, int64_t y0, int64_t x1, int64_t y1) {
    const std::vector<IPoint> r = {{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}};
    std::vector<DirectedEdge> e;
    for (size_t i = 0; i < 4; ++i) e.push_back({r[i], r[(i + 1) % 4], 1});
    return e;
}

}  // namespace ss::planar::test
