// How a pass becomes an 8-bit grayscale PNG preview (V in [0,1] -> 0..255) for demos and docs.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

#include "core/image.h"
#include "io/atomic_file.h"

namespace ss {

// Writes atomically; throws ss::Error(SS_ERROR_IO) naming the path when it cannot.
void writePngPreview(const std::string& path, const Image& image);

// Writes the preview beside `path` without replacing it yet (commit() does), so a batch of
// outputs either all replace their old files or all leave them as they were.
StagedFile stagePngPreview(const std::string& path, const Image& image);

// A pass name as a file name inside a preview folder: path separators, control characters and
// a leading dot become "_", so no light name reaches outside the folder or hides a file.
std::string previewFileName(const std::string& pass);

}  // namespace ss
