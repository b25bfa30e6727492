// Where the point samples of a light go: an irregular, border-preferring, seed-deterministic
// set for every light shape (disk, ellipse, square, rectangle, sphere seen from the occluders,
// sun by angle).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/light.h"

namespace ss {

struct LightSample {
    glm::dvec3 point{0.0};      // world position (positional lights)
    glm::dvec3 toLight{0.0};    // unit direction towards the light (sun only)
    bool directional = false;
};

struct LightSampleOptions {
    int count = 16;
    uint32_t seed = 1;
    // Share of the samples placed on the light's border (at least 3 when count >= 3): the border
    // samples fix where the penumbra starts and ends; the rest spread over the inside by area.
    double borderShare = 0.25;
    // One of `sets` sample sets meant to be used together (the sweep's passes): set k's
    // strata are offset by k / sets of a stratum, so the sets interleave instead of repeating
    // the same rows and columns. One set: the plain pattern.
    int set = 0, sets = 1;
    // Sphere lights (point/spot with a radius) are seen from here as a disk facing this point.
    glm::dvec3 viewFrom{0.0};
};

// count 1 (or a light with no extent: radius 0, sun angle 0) gives the light's centre.
std::vector<LightSample> placeLightSamples(const Light& light, const LightSampleOptions& options);

// The unit-domain pattern behind placeLightSamples: points in the unit disk (round shapes) or
// in [-1,1]^2 (square shapes); exposed for tests.
std::vector<glm::dvec2> unitSamplePattern(bool square, int count, uint32_t seed, double borderShare, int set = 0,
                                          int sets = 1);

}  // namespace ss
