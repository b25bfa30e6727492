// How each Blender light shape is mapped onto the disk light the dbuffer method needs.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "core/light.h"
#include "core/scene.h"
#include "geometry/silhouette.h"

namespace ss {

// The disk the dbuffer method uses for `light` (docs/methods/dbuffer.md, "Light shapes"):
// - DISK: itself. ELLIPSE, SQUARE, RECTANGLE: the area-equal disk (Light::equivalentRadius) in
//   the light's own plane: it keeps the emitted power per solid angle and the mean penumbra width.
// - POINT/SPOT with a radius (a sphere): the sphere's great disk facing the casters' bounds
//   centre (the sphere's silhouette as the occluders see it).
// - SUN: a disk at distance 20 × the scene diagonal against the sun direction from the scene
//   centre, of the radius that subtends the sun's angular diameter there.
// `casters` are the bounds of the casting meshes (used for point/spot and sun).
Disk dbufferDisk(const Light& light, const Bounds& casters, const Bounds& scene);

}  // namespace ss
