// Where the 2D sample points over a light come from: Owen-scrambled Sobol, one scramble per pixel.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace ss {

// The first two Sobol dimensions form a (0,2)-sequence: any power-of-two prefix stratifies the
// unit square in every elementary interval. A hash-based nested uniform (Owen) scramble keeps
// that stratification while decorrelating pixels, so the error is never worse than plain Monte
// Carlo and falls faster near shadow edges. Everything is a pure function of (index, scramble):
// results do not depend on thread count or pixel order.
class SampleSequence {
public:
    // `seed` is the render seed; (x, y) the pixel (or any two integers naming a point).
    SampleSequence(uint32_t seed, uint32_t x, uint32_t y);
    // Point `index` of the sequence, in [0, 1)^2.
    glm::vec2 point(uint32_t index) const;

private:
    uint32_t scrambleX_, scrambleY_;
};

// A 32-bit integer hash with full avalanche (lowbias32); also used to derive per-pixel seeds.
uint32_t hashU32(uint32_t x);

}  // namespace ss
