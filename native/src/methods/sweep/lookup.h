// How the shadow mesh is evaluated at a receiver point on the CPU: a bucket grid over its
// triangles and barycentric interpolation of the vertex intensities.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <vector>

#include "planar/penumbra_fill.h"

namespace ss {

class ShadowLookup {
public:
    explicit ShadowLookup(const planar::ShadowMesh& mesh);
    // Shadow intensity at grid point (x, y): 0 where no triangle covers it.
    float intensity(double x, double y) const;

private:
    const planar::ShadowMesh& mesh_;
    double x0_ = 0, y0_ = 0, cell_ = 1;
    int nx_ = 0, ny_ = 0;
    std::vector<uint32_t> start_, items_;  // CSR buckets of triangle indices
};

}  // namespace ss
