// How passes become a multilayer float EXR through OpenEXR's own API, and how one is read back.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/exr_file.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <fstream>
#include <set>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/openexr.h>

#include "core/camera.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "io/pass_names.h"

namespace ss {

namespace {

void checkPasses(const std::string& path, const std::string& viewLayer,
                 const std::vector<ExrPassRef>& passes) {
    auto bad = [&](const std::string& what) {
        fail(SS_ERROR_INVALID_ARGUMENT, "cannot write EXR '" + path + "': " + what);
    };
    if (viewLayer.empty()) bad("the view layer name is empty");
    if (passes.empty()) bad("there are no passes to write");
    std::set<std::string> seen;
    const Image* first = passes.front().image;
    for (const ExrPassRef& p : passes) {
        checkPassName(path, viewLayer, p.pass);
        if (!seen.insert(p.pass).second) bad("pass '" + p.pass + "' appears twice");
        if (!p.image || p.image->width <= 0 || p.image->height <= 0 ||
            p.image->pixels.size() != size_t(p.image->width) * p.image->height)
            bad("pass '" + p.pass + "' has no pixels");
        if (p.image->width != first->width || p.image->height != first->height)
            bad("pass '" + p.pass + "' is " + std::to_string(p.image->width) + "x" +
                std::to_string(p.image->height) + " but '" + passes.front().pass + "' is " +
                std::to_string(first->width) + "x" + std::to_string(first->height));
    }
}

// A band of rows of every pass at a time: OpenEXR gets them as slices of one buffer.
constexpr uint64_t kBandBytes = 64ull << 20;

void writeExrBands(const std::string& file, const std::string& shownPath, const std::string& viewLayer, int w,
                   int h, const std::vector<ExrPassRows>& passes, const std::string& methods) {
    const size_t n = passes.size();
    const uint64_t rowBytes = uint64_t(w) * sizeof(float) * n;
    Imf::Header header(w, h);
    // ZIP packs 16 rows a chunk and OpenEXR buffers a whole chunk: with very wide rows of many
    // passes, ZIPS (one row a chunk) keeps that buffer small.
    header.compression() = rowBytes * 16 > kBandBytes ? Imf::ZIPS_COMPRESSION : Imf::ZIP_COMPRESSION;
    header.insert("Software", Imf::StringAttribute("softshadow " SS_VERSION));
    if (!methods.empty()) header.insert(kExrMethodsAttribute, Imf::StringAttribute(methods));
    for (const ExrPassRows& p : passes) header.channels().insert(channelName(viewLayer, p.pass), Imf::Channel(Imf::FLOAT));
    const int band = int(std::clamp<uint64_t>(kBandBytes / std::max<uint64_t>(rowBytes, 1), 1, uint64_t(h)));
    const size_t passFloats = size_t(band) * size_t(w);
    std::vector<float> buffer(passFloats * n);
    try {
        Imf::OutputFile out(file.c_str(), header);
        for (int y0 = 0; y0 < h; y0 += band) {
            const int rows = std::min(band, h - y0);
            Imf::FrameBuffer frame;
            for (size_t c = 0; c < n; ++c) {
                float* first = buffer.data() + c * passFloats;
                passes[c].read(y0, rows, first);
                // OpenEXR addresses a slice by absolute row: shift the base so row y0 lands on `first`.
                char* base = reinterpret_cast<char*>(reinterpret_cast<intptr_t>(first) -
                                                     intptr_t(y0) * intptr_t(w) * intptr_t(sizeof(float)));
                frame.insert(channelName(viewLayer, passes[c].pass),
                             Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
            }
            out.setFrameBuffer(frame);
            out.writePixels(rows);
        }
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail(SS_ERROR_IO, "cannot write EXR '" + shownPath + "': " + e.what());
    }
}

// Splits "<layer>.<pass>.<channel>" the way Blender does: the last token is the channel, the
// one before it the pass, everything before that the layer.
void splitChannelName(const std::string& full, ExrPass& p) {
    size_t last = full.rfind('.');
    if (last == std::string::npos) {
        p.pass = full;
        return;
    }
    p.channel = full.substr(last + 1);
    size_t prev = last == 0 ? std::string::npos : full.rfind('.', last - 1);
    if (prev == std::string::npos) {
        p.pass = full.substr(0, last);
    } else {
        p.layer = full.substr(0, prev);
        p.pass = full.substr(prev + 1, last - prev - 1);
    }
}

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

// OpenEXR's C++ reader allocates each header attribute at its declared size before reading it:
// walk the header(s) first and refuse an attribute larger than the rest of the file.
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
        token("attribute type");
        if (at + 4 > head.size()) bad("its header ends inside attribute '" + name + "'");
        int32_t size = 0;
        std::memcpy(&size, head.data() + at, 4);
        at += 4;
        if (size < 0 || uint64_t(size) > fileBytes - at)
            bad("header attribute '" + name + "' declares " + std::to_string(size) + " bytes, more than the " +
                std::to_string(fileBytes - at) + " left in the file");
        if (at + size_t(size) > head.size()) bad("its header is longer than 16 MiB");
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

void writeMultilayerExr(const std::string& path, const std::string& viewLayer,
                        const std::vector<ExrPassRef>& passes, const std::string& methods) {
    checkPasses(path, viewLayer, passes);
    const int w = passes.front().image->width, h = passes.front().image->height;
    checkExrShape(path, passes.size(), w);
    std::vector<ExrPassRows> rows;
    for (const ExrPassRef& p : passes) {
        const Image* image = p.image;
        rows.push_back({p.pass, [image, w](int y0, int count, float* out) {
                            std::copy_n(image->pixels.data() + size_t(y0) * w, size_t(count) * w, out);
                        }});
    }
    writeMultilayerExrRows(path, viewLayer, w, h, rows, methods);
}

void checkPassName(const std::string& path, const std::string& viewLayer, const std::string& pass) {
    auto bad = [&](const std::string& what) {
        fail(SS_ERROR_INVALID_ARGUMENT, "cannot write EXR '" + path + "': " + what);
    };
    if (pass.empty() || pass.find('.') != std::string::npos) bad("pass name '" + pass + "' is empty or has a dot");
    std::string channel = channelName(viewLayer, pass);
    if (channel.size() > kMaxExrChannelBytes)
        bad("channel '" + channel + "' is " + std::to_string(channel.size()) + " bytes, longer than EXR's " +
            std::to_string(kMaxExrChannelBytes));
}

void checkExrShape(const std::string& path, size_t passes, int width) {
    auto bad = [&](const std::string& what) {
        fail(SS_ERROR_INVALID_ARGUMENT, "cannot write EXR '" + path + "': " + what);
    };
    if (passes > kMaxExrWriteChannels)
        bad(std::to_string(passes) + " passes (at most " + std::to_string(kMaxExrWriteChannels) + ")");
    const uint64_t rowBytes = uint64_t(width) * sizeof(float) * passes;
    if (rowBytes > kMaxExrRowBytes)
        bad(std::to_string(passes) + " passes " + std::to_string(width) + " pixels wide make rows of " +
            std::to_string(rowBytes) + " bytes (at most " + std::to_string(kMaxExrRowBytes) + ")");
}

void writeMultilayerExrRows(const std::string& path, const std::string& viewLayer, int width, int height,
                            const std::vector<ExrPassRows>& passes, const std::string& methods) {
    checkExrShape(path, passes.size(), width);
    writeAtomically(path, [&](const std::string& temp) { writeExrBands(temp, path, viewLayer, width, height, passes, methods); });
}

const ExrPass* ExrContents::find(const std::string& pass) const {
    for (const ExrPass& p : passes)
        if (p.pass == pass) return &p;
    return nullptr;
}

ExrContents readMultilayerExr(const std::string& path) {
    ExrContents contents;
    const uint64_t fileBytes = checkInputFile(path, "EXR");
    checkAttributeSizes(path, fileBytes);
    checkDeclaredSize(path, fileBytes, readDeclaredSize(path));
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i window = in.header().dataWindow();
        const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
        contents.width = w;
        contents.height = h;
        Imf::FrameBuffer frame;
        const Imf::ChannelList& channels = in.header().channels();
        for (auto c = channels.begin(); c != channels.end(); ++c) {
            ExrPass p;
            splitChannelName(c.name(), p);
            p.image = Image(w, h);
            contents.passes.push_back(std::move(p));
        }
        size_t index = 0;
        for (auto c = channels.begin(); c != channels.end(); ++c, ++index) {
            // OpenEXR addresses a slice by absolute pixel coordinates: shift the base so the data
            // window's corner lands on the first element.
            float* first = contents.passes[index].image.pixels.data();
            char* base = reinterpret_cast<char*>(first - window.min.x - ptrdiff_t(window.min.y) * w);
            frame.insert(c.name(), Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
        }
        in.setFrameBuffer(frame);
        in.readPixels(window.min.y, window.max.y);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail(SS_ERROR_IO, "cannot read EXR '" + path + "': " + e.what());
    }
    return contents;
}

}  // namespace ss
