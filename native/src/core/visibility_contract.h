// Which points a light reaches (E_L > 0): the CPU mask, a copy of common/visibility_contract.glsl.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <glm/glm.hpp>

#include "core/light.h"

namespace ss {

// P: world point, N: unit geometric normal facing the viewer. True exactly when the `reference`
// method's light samples (reference/light_sampler.h) can carry weight to P above its horizon:
// - area: P strictly in front of the one-sided light, and some point of the shape above P's
//   tangent plane;
// - point/spot of radius r: P outside the sphere, and some point of the disk of radius r
//   centred on the light and facing P (Cycles 3.0-3.4) above P's tangent plane; a spot also
//   needs some point of that disk to see P inside its cone (Cycles' blend smoothstep is > 0 up
//   to the cone's edge, so the blend does not shrink the region);
// - sun: some direction of the sun's cone above P's tangent plane.
// A spot needs one point of the disk to satisfy both (cone and horizon), tested exactly on the
// lens where the disk and the cone overlap as seen from P.
// Same code as lightReaches() in shaders/common/visibility_contract.glsl; keep the two identical.
bool lightReaches(const Light& light, const glm::vec3& P, const glm::vec3& N);

}  // namespace ss
