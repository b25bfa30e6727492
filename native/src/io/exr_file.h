// How visibility passes are written to and read from a multilayer EXR that Blender lists as
// passes of one image (channel "<view_layer>.<pass>.V", float32, written atomically).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace ss {

// One pass to write: its pass name (see io/pass_names.h) and its pixels.
struct ExrPassRef {
    std::string pass;
    const Image* image = nullptr;
};

// The header attribute that records which method made each pass ("<pass>=<method>;...").
inline constexpr const char* kExrMethodsAttribute = "softshadow/methods";

// Writes every pass as channel "<viewLayer>.<pass>.V" (all the same size) to a temporary file
// in the destination folder, then renames it over `path`, so a reader never sees a half-written
// file. Throws ss::Error(SS_ERROR_IO) naming the path when it cannot be written (and leaves no
// file behind), SS_ERROR_INVALID_ARGUMENT for empty/duplicate/misshapen passes.
// `methods`, when not empty, goes in the header as kExrMethodsAttribute.
void writeMultilayerExr(const std::string& path, const std::string& viewLayer,
                        const std::vector<ExrPassRef>& passes, const std::string& methods = {});

struct ExrPass {
    std::string layer;    // the view layer (everything before the pass token)
    std::string pass;     // e.g. "Area_reference" or "Area_reference_mask"
    std::string channel;  // e.g. "V"
    Image image;
};

struct ExrContents {
    int width = 0, height = 0;
    std::vector<ExrPass> passes;  // in the file's channel order
    const ExrPass* find(const std::string& pass) const;
};

// Reads every channel of an EXR. A channel name without two dots is kept with an empty layer
// (and pass = the name before the last dot, or the whole name). Throws SS_ERROR_IO naming the path.
ExrContents readMultilayerExr(const std::string& path);

}  // namespace ss
