// How an EXR's header is checked against its file and the limits before it is read.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/exr_limits.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <utility>

#include <OpenEXR/openexr.h>

#include "core/camera.h"
#include "core/error.h"
#include "io/exr_file.h"
#include "io/input_file.h"

namespace ss {

namespace {

// zlib cannot shrink data more than about 1032:1; a file claiming more is lying about its size.
constexpr uint64_t kMaxDeflateRatio = 1100;

// What an EXR header declares, read with OpenEXR's core API, which reads the header alone:
// its C++ API builds tables sized from the header before we can look at it.
struct DeclaredSize {
    int64_t width = 0, height = 0;
    size_t channels = 0;
    uint64_t storedBytes = 0;  // the pixels as stored uncompressed
    bool deflateOrRaw = false;
};

thread_local std::string coreError;

void rememberCoreError(exr_const_context_t, exr_result_t, const char* message) {
    coreError = message ? message : "";
}

DeclaredSize readDeclaredSize(const std::string& path) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = rememberCoreError;  // no printing to stderr
    exr_context_t ctxt = nullptr;
    coreError.clear();
    auto bad = [&](const std::string& what) { fail(SS_ERROR_IO, "cannot read EXR '" + path + "': " + what); };
    if (exr_start_read(&ctxt, path.c_str(), &init) != EXR_ERR_SUCCESS) {
        exr_finish(&ctxt);
        bad(coreError.empty() ? std::string("not an OpenEXR file") : coreError);
    }
    DeclaredSize d;
    exr_attr_box2i_t box{};
    const exr_attr_chlist_t* channels = nullptr;
    exr_compression_t compression = EXR_COMPRESSION_NONE;
    bool ok = exr_get_data_window(ctxt, 0, &box) == EXR_ERR_SUCCESS &&
              exr_get_channels(ctxt, 0, &channels) == EXR_ERR_SUCCESS && channels &&
              exr_get_compression(ctxt, 0, &compression) == EXR_ERR_SUCCESS;
    if (ok) {
        d.width = int64_t(box.max.x) - box.min.x + 1;
        d.height = int64_t(box.max.y) - box.min.y + 1;
        d.channels = size_t(std::max(0, channels->num_channels));
        d.deflateOrRaw = compression == EXR_COMPRESSION_NONE || compression == EXR_COMPRESSION_RLE ||
                         compression == EXR_COMPRESSION_ZIPS || compression == EXR_COMPRESSION_ZIP;
        const uint64_t pixels = d.width > 0 && d.height > 0 ? uint64_t(d.width) * uint64_t(d.height) : 0;
        for (int i = 0; i < channels->num_channels; ++i) {
            const exr_attr_chlist_entry_t& c = channels->entries[i];
            uint64_t sampling = uint64_t(std::max(1, c.x_sampling)) * uint64_t(std::max(1, c.y_sampling));
            d.storedBytes += pixels * (c.pixel_type == EXR_PIXEL_HALF ? 2u : 4u) / sampling;
        }
    }
    exr_finish(&ctxt);
    if (!ok) bad(coreError.empty() ? std::string("its header has no data window or channels") : coreError);
    return d;
}

// The bytes OpenEXR's reader takes for a value of a fixed-size type, whatever the header declares
// (0: the type's size is the declared one, or is found by reading it: chlist, preview).
size_t fixedValueBytes(const std::string& type) {
    static const std::pair<const char*, size_t> kSizes[] = {
        {"box2i", 16}, {"box2f", 16},   {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
        {"double", 8}, {"envmap", 1},   {"float", 4},           {"int", 4},         {"keycode", 28},
        {"lineOrder", 1}, {"m33f", 36}, {"m33d", 72},           {"m44f", 64},       {"m44d", 128},
        {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},      {"v2i", 8},         {"v2f", 8},
        {"v2d", 16},   {"v3i", 12},     {"v3f", 12},            {"v3d", 24}};
    for (const auto& [name, bytes] : kSizes)
        if (type == name) return bytes;
    return 0;
}

// OpenEXR's C++ reader allocates each header attribute at its declared size before reading it,
// and reads a value of a fixed-size type, a channel list or a preview by its own length, not the
// declared one: walk the header(s) first as it does, and refuse an attribute larger than the rest
// of the file or whose declared size is not what the reader will take (after it, the two would
// part and the reader would take later bytes for sizes).
void checkAttributeSizes(const std::string& path, uint64_t fileBytes) {
    auto bad = [&](const std::string& what) { fail(SS_ERROR_IO, "cannot read EXR '" + path + "': " + what); };
    constexpr uint64_t kMaxHeaderBytes = 16u << 20;
    std::string head(size_t(std::min(fileBytes, kMaxHeaderBytes)), '\0');
    {
        std::ifstream in(path, std::ios::binary);
        in.read(head.data(), std::streamsize(head.size()));
        head.resize(size_t(std::max<std::streamsize>(0, in.gcount())));
    }
    if (head.size() < 8) bad("it is too short for an OpenEXR file");
    if (std::memcmp(head.data(), "\x76\x2f\x31\x01", 4) != 0)
        bad("it is not an OpenEXR file (it does not start with EXR's magic number 76 2f 31 01)");
    // Version flags (bits 9, 11, 12): tiled, deep and multi-part files size tables from their
    // headers in ways the checks below do not bound; softshadow and Blender write neither.
    const uint8_t flags = uint8_t(head[5]);
    if (flags & 0x02) bad("it is tiled (allowed: single-part scanline EXRs, as softshadow and Blender write)");
    if (flags & 0x08) bad("it holds deep data (allowed: single-part scanline EXRs, as softshadow and Blender write)");
    if (flags & 0x10) bad("it is multi-part (allowed: single-part scanline EXRs, as softshadow and Blender write)");
    size_t at = 8;
    auto token = [&](const char* what) {
        size_t end = head.find('\0', at);
        if (end == std::string::npos || end - at > 255)
            bad(std::string("its header has no proper ") + what + " (or is longer than 16 MiB)");
        at = end + 1;
    };
    while (at < head.size() && head[at] != '\0') {
        size_t nameAt = at;
        token("attribute name");
        std::string name = head.substr(nameAt, at - nameAt - 1);
        const size_t typeAt = at;
        token("attribute type");
        const std::string type = head.substr(typeAt, at - typeAt - 1);
        if (at + 4 > head.size()) bad("its header ends inside attribute '" + name + "'");
        int32_t size = 0;
        std::memcpy(&size, head.data() + at, 4);
        at += 4;
        if (size < 0 || uint64_t(size) > fileBytes - at)
            bad("header attribute '" + name + "' declares " + std::to_string(size) + " bytes, more than the " +
                std::to_string(fileBytes - at) + " left in the file");
        if (at + size_t(size) > head.size()) bad("its header is longer than 16 MiB");
        size_t taken = fixedValueBytes(type);
        if (type == "chlist") {
            // Entries of a name and 16 bytes, up to an empty name.
            size_t p = at;
            while (p < at + size_t(size) && head[p] != '\0') {
                const size_t end = head.find('\0', p);
                if (end == std::string::npos) break;
                p = end + 1 + 16;
            }
            taken = p + 1 - at;
        } else if (type == "preview" && size >= 8) {
            uint32_t w = 0, h = 0;
            std::memcpy(&w, head.data() + at, 4);
            std::memcpy(&h, head.data() + at + 4, 4);
            const uint64_t pixels = uint64_t(w) * uint64_t(h);  // below 2^64
            taken = pixels > fileBytes ? size_t(size) + 1 : size_t(8 + 4 * pixels);
        }
        if (taken != 0 && taken != size_t(size))
            bad("header attribute '" + name + "' of type '" + type + "' declares " + std::to_string(size) +
                " bytes where its value takes " + std::to_string(taken));
        at += size_t(size);
    }
    if (at >= head.size()) bad("its header ends early (or is longer than 16 MiB)");
}

// Refuses, before any pixel buffer exists, a header whose pixels would not fit the limits or
// could not have come from a file this size (a small file declaring a huge image).
void checkDeclaredSize(const std::string& path, uint64_t fileBytes, const DeclaredSize& d) {
    auto bad = [&](const std::string& what) { fail(SS_ERROR_IO, "cannot read EXR '" + path + "': " + what); };
    const std::string size = std::to_string(d.width) + "x" + std::to_string(d.height);
    if (d.width <= 0 || d.height <= 0) bad("its data window " + size + " is empty");
    const uint64_t pixels = uint64_t(d.width) * uint64_t(d.height);
    if (d.width > kMaxCameraSide || d.height > kMaxCameraSide || pixels > uint64_t(kMaxCameraPixels))
        bad("it declares " + size + " pixels (at most " + std::to_string(kMaxCameraPixels) +
            ", 8192 x 8192, sides up to " + std::to_string(kMaxCameraSide) + ")");
    if (d.channels > kMaxExrChannels)
        bad("it declares " + std::to_string(d.channels) + " channels (at most " + std::to_string(kMaxExrChannels) + ")");
    const uint64_t bytes = pixels * d.channels * sizeof(float);
    if (bytes > kMaxExrReadBytes)
        bad("its " + std::to_string(d.channels) + " channels of " + size + " need " + std::to_string(bytes) +
            " bytes (at most " + std::to_string(kMaxExrReadBytes) + ")");
    if (d.deflateOrRaw && d.storedBytes > fileBytes * kMaxDeflateRatio)
        bad("it declares " + size + " pixels in " + std::to_string(d.channels) + " channels, more than its " +
            std::to_string(fileBytes) + " bytes can hold");
}

}  // namespace

void checkExrBeforeReading(const std::string& path) {
    const uint64_t fileBytes = checkInputFile(path, "EXR");
    checkAttributeSizes(path, fileBytes);
    checkDeclaredSize(path, fileBytes, readDeclaredSize(path));
}

}  // namespace ss
