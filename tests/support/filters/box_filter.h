// How a box-filtered occlusion texture is computed on the CPU (the GL pre-filters' references).
// SPDX-License-Identifier: GPL-3.0-or-later
// Brute force, summed-area table, N-Buffers and mipmaps, as occlusion_textures' tests use them.
#pragma once
#include <cstddef>
#include <vector>

namespace ss::filters {

// One channel of a texture. Texel (i, j) covers [i, i+1] x [j, j+1] in continuous texel
// coordinates; everything outside the texture is 0 (no occluder outside the slicing frustum).
struct Plane {
    int width = 0, height = 0;
    std::vector<float> texels;  // row-major, row j = texel row j (GL's t = (j + 0.5) / height)

    Plane() = default;
    Plane(int w, int h, float fill = 0.0f) : width(w), height(h), texels(std::size_t(w) * h, fill) {}
    float at(int i, int j) const {
        return (i < 0 || j < 0 || i >= width || j >= height) ? 0.0f : texels[std::size_t(j) * width + i];
    }
    float& at(int i, int j) { return texels[std::size_t(j) * width + i]; }
};

// Mean of the texture over the box [x0, x1] x [y0, y1] (texel units, fractional edges count
// the covered part of a texel): the exact box filter, by summing every texel.
double boxBrute(const Plane& p, double x0, double y0, double x1, double y1);

// Summed-area table with a zero first row and column: F(i, j) = sum of texels i' < i, j' < j.
struct SummedAreaTable {
    int width = 0, height = 0;  // of the texture; the table is (width + 1) x (height + 1)
    std::vector<float> table;
    float F(int i, int j) const;  // clamped to the table
    static SummedAreaTable build(const Plane& p);
    // The exact box mean: F is bilinear inside each texel cell, and the corner differences are
    // taken between integer sums first so that small boxes keep their precision in float.
    float box(float x0, float y0, float x1, float y1) const;
};

// N-Buffers: level l holds, at texel (i, j), the mean of the 2^l x 2^l box whose lower corner
// is texel (i, j); every level at full resolution.
struct NBuffer {
    int width = 0, height = 0;
    std::vector<Plane> levels;
    static NBuffer build(const Plane& p);
    // Bilinear sample of one level at a continuous texel coordinate (centres at i + 0.5).
    float sample(int level, float x, float y) const;
    // The approximate mean over a box of size w x h centred at (cx, cy): the level pair that
    // brackets min(w, h), linear in the size between them; a rectangular box averages
    // square lookups spread along its long side. Same rule as the GLSL.
    float box(float cx, float cy, float w, float h) const;
};

// A mipmap pyramid (2x2 means, odd sizes rounded down like GL) and trilinear / anisotropic
// sampling in the way the GL texture unit does it.
struct Mipmap {
    std::vector<Plane> levels;
    static Mipmap build(const Plane& p);
    float bilinear(int level, float u, float v) const;  // u, v in [0, 1], clamp to border 0
    // Mean over a box of w x h texels (of level 0) centred at (cx, cy): trilinear at the lod of
    // the short side, with ceil(long / short) probes along the long side (anisotropic filter).
    float box(float cx, float cy, float w, float h) const;
};

}  // namespace ss::filters
