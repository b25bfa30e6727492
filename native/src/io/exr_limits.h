// Whether an EXR may be read at all: a regular file whose header fits in the file and whose
// declared pixels fit the limits, checked before OpenEXR's reader sizes anything from it.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

namespace ss {

// Throws ss::Error(SS_ERROR_IO) "cannot read EXR '<path>': <why>" (docs/reliability.md, limits):
// not a regular file; tiled, deep or multi-part; a header attribute larger than the rest of the
// file, or whose declared size is not what its value takes; more pixels, channels or float bytes than the limits in io/exr_file.h; more pixels than a
// zip/rle/uncompressed file this size can hold.
void checkExrBeforeReading(const std::string& path);

}  // namespace ss
