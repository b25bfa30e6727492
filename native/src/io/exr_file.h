// How visibility passes are written to and read from a multilayer EXR that Blender lists as
// passes of one image (channel "<view_layer>.<pass>.V", float32, written atomically).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <functional>
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
// The header attribute that records each main pass's estimated RMSE against the reference (the
// sparse exact check, methods/sparse_check.h): "<pass>=<rmse>;...", only passes that have one.
inline constexpr const char* kExrEstimatesAttribute = "softshadow/estimated_rmse";

// How an estimate is written in kExrEstimatesAttribute: "%.6g".
std::string formatEstimate(double rmse);

// Writes every pass as channel "<viewLayer>.<pass>.V" (all the same size) to a temporary file
// in the destination folder, then renames it over `path`, so a reader never sees a half-written
// file. Throws ss::Error(SS_ERROR_IO) naming the path when it cannot be written (and leaves no
// file behind), SS_ERROR_INVALID_ARGUMENT for empty/duplicate/misshapen passes.
// `methods`, when not empty, goes in the header as kExrMethodsAttribute, `estimates` as
// kExrEstimatesAttribute.
void writeMultilayerExr(const std::string& path, const std::string& viewLayer,
                        const std::vector<ExrPassRef>& passes, const std::string& methods = {},
                        const std::string& estimates = {});

// A pass whose rows are read on demand (from memory, or from a spool file, io/exr_spool.h):
// read(y0, rows, out) fills rows x width floats, row y0 first (row 0 = top).
struct ExrPassRows {
    std::string pass;
    std::function<void(int y0, int rows, float* out)> read;
};

// What one EXR may hold when written: channels, and bytes of one row of every channel (the
// writer holds a band of rows at a time, at least one).
inline constexpr size_t kMaxExrWriteChannels = 16384;
inline constexpr uint64_t kMaxExrRowBytes = 256ull << 20;

// As writeMultilayerExr, fetching the pixels band by band, so memory stays within a band of
// rows (about 64 MiB) however many passes there are. The caller has checked the pass names.
void writeMultilayerExrRows(const std::string& path, const std::string& viewLayer, int width, int height,
                            const std::vector<ExrPassRows>& passes, const std::string& methods = {},
                            const std::string& estimates = {});

// OpenEXR cuts longer channel names, and cut names collide.
inline constexpr size_t kMaxExrChannelBytes = 255;

// Throws SS_ERROR_INVALID_ARGUMENT naming `path` unless `pass` is a non-empty name without dots
// whose channel "<viewLayer>.<pass>.V" fits kMaxExrChannelBytes.
void checkPassName(const std::string& path, const std::string& viewLayer, const std::string& pass);

// Throws SS_ERROR_INVALID_ARGUMENT naming `path` when passes of this count and width could not
// be written within the limits above.
void checkExrShape(const std::string& path, size_t passes, int width);

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

// What readMultilayerExr accepts (docs/reliability.md): the pixel count of a camera
// (core/camera.h), these many channels, these many bytes of float pixels in all.
inline constexpr size_t kMaxExrChannels = 4096;
inline constexpr uint64_t kMaxExrReadBytes = 4ull << 30;

// Reads every channel of an EXR (header checked against the limits before any pixel buffer). A channel name without two dots is kept with an empty layer
// (and pass = the name before the last dot, or the whole name). Throws SS_ERROR_IO naming the path.
ExrContents readMultilayerExr(const std::string& path);

}  // namespace ss
