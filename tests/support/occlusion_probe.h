// How the tests reach occlusion_textures' GL pre-filters directly: upload a slice group and
// evaluate the GLSL boxFilter() at chosen boxes (test support, not in the shipped library).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "methods/occlusion_textures/prefilter.h"

namespace ss::occlusion {

// Evaluates the GLSL boxFilter of `filtered` for group `group` at each query
// (centre.x, centre.y, width, height in texels) and returns the RGBA responses.
std::vector<glm::vec4> probeFilter(const FilteredSlices& filtered, int group, const std::vector<glm::vec4>& queries);
// Uploads RGBA texels (row 0 first) into level 0 of a group texture.
void uploadGroup(const SliceTextures& slices, int group, const std::vector<float>& rgba);

}  // namespace ss::occlusion
