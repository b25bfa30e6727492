// Which passes of one or two visibility EXRs are compared, and their error numbers (what
// `softshadow compare` prints, through ss_compare_exr).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

namespace ss {

// Pairs the passes of `pathA` and `pathB` that share a name; with none (or with pathB empty:
// one file), each method's visibility pass against the `against` method's pass of the same light
// and layer. Each pair is compared over `maskPass`: "" = the pixels both passes' own masks hold,
// "none" = every pixel, else the pass of that name. Returns a JSON array of rows
// {"a", "b", "mask", "pixels", "rmse", "mean", "p99", "max", "umbra_iou", "lit_iou"}.
// Throws ss::Error: SS_ERROR_IO for a file that cannot be read, SS_ERROR_INVALID_ARGUMENT when
// nothing pairs or the mask pass does not exist.
std::string compareExrFiles(const std::string& pathA, const std::string& pathB, const std::string& against,
                            const std::string& maskPass);

}  // namespace ss
