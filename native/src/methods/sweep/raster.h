// How the sweep shadow mesh is drawn into the camera view with GL (the camera's own matrices and
// pixel centres); the caller masks it with the camera pass so occluders in front hide it.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "core/image.h"
#include "methods/sweep/shadow.h"
#include "frame/frame.h"

namespace ss {

// Shadow intensity per camera pixel (row 0 = top); 0 where no shadow triangle is drawn.
// Must run on the render thread.
Image rasterSweepShadow(Frame& frame, const SweepShadow& shadow);

}  // namespace ss
