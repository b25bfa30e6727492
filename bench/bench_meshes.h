// Which meshes the stage benchmarks draw: a UV sphere of a chosen size over a ground square.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "core/mesh.h"

namespace ss::bench {

// A closed UV sphere with 4 m² triangles (poles as fans), radius r at c, outward winding:
// m = 16, 35, 50, 71, 158, 274, 500 give 1k, 4.9k, 10k, 20k, 100k, 300k, 1M triangles.
Mesh uvSphere(int m, float r, glm::vec3 c, uint32_t flags);
// An upward square of half size `half` at z = 0, casting and receiving.
Mesh groundSquare(float half);

}  // namespace ss::bench
