// Which points a light reaches at all (E_L > 0, DESIGN.md "Visibility"): the mask, on the CPU.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <glm/glm.hpp>

#include "core/light.h"

namespace ss {

// P: world point, N: unit geometric normal facing the viewer. True when some part of the light
// both emits towards P and lies above P's horizon. Same rule as lightReaches() in
// shaders/common/visibility_contract.glsl; keep the two identical.
bool lightReaches(const Light& light, const glm::vec3& P, const glm::vec3& N);

}  // namespace ss
