// How receiver-plane coordinates are snapped to the integer grid of the exact predicates, and
// how edges leaving the receiver's box are clipped so winding inside the box is unchanged.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <vector>

#include "planar/sweep_line.h"

namespace ss::planar {

class Snap {
public:
    // The square box centred on (cu, cv) with half side `half` maps onto [-kGridLimit, kGridLimit].
    Snap(double cu, double cv, double half);
    double scale() const { return scale_; }
    // Grid (continuous) -> plane coordinates.
    double toU(double gx) const { return cu_ + gx / scale_; }
    double toV(double gy) const { return cv_ + gy / scale_; }
    // Adds the directed plane edge a->b: split where it crosses the box's four lines, every
    // piece clamped onto the box (clamping is affine on each piece, so the winding number of
    // every point inside the box is kept), then rounded to the grid.
    void addEdge(double ua, double va, double ub, double vb, int weight, std::vector<DirectedEdge>* out) const;

private:
    double cu_, cv_, scale_;
};

}  // namespace ss::planar
