// How passes become a multilayer float EXR through OpenEXR's own API, and how one is read back.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/exr_file.h"

#include <cstdio>
#include <algorithm>
#include <exception>
#include <set>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/exr_limits.h"
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
                   int h, const std::vector<ExrPassRows>& passes, const std::string& methods,
                   const std::string& estimates) {
    const size_t n = passes.size();
    const uint64_t rowBytes = uint64_t(w) * sizeof(float) * n;
    Imf::Header header(w, h);
    // ZIP packs 16 rows a chunk and OpenEXR buffers a whole chunk: with very wide rows of many
    // passes, ZIPS (one row a chunk) keeps that buffer small.
    header.compression() = rowBytes * 16 > kBandBytes ? Imf::ZIPS_COMPRESSION : Imf::ZIP_COMPRESSION;
    header.insert("Software", Imf::StringAttribute("softshadow " SS_VERSION));
    if (!methods.empty()) header.insert(kExrMethodsAttribute, Imf::StringAttribute(methods));
    if (!estimates.empty()) header.insert(kExrEstimatesAttribute, Imf::StringAttribute(estimates));
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

}  // namespace

std::string formatEstimate(double rmse) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", rmse);
    return text;
}

void writeMultilayerExr(const std::string& path, const std::string& viewLayer,
                        const std::vector<ExrPassRef>& passes, const std::string& methods,
                        const std::string& estimates) {
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
    writeMultilayerExrRows(path, viewLayer, w, h, rows, methods, estimates);
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
                            const std::vector<ExrPassRows>& passes, const std::string& methods,
                            const std::string& estimates) {
    checkExrShape(path, passes.size(), width);
    writeAtomically(path, [&](const std::string& temp) { writeExrBands(temp, path, viewLayer, width, height, passes, methods, estimates);
    });
}

const ExrPass* ExrContents::find(const std::string& pass) const {
    for (const ExrPass& p : passes)
        if (p.pass == pass) return &p;
    return nullptr;
}

ExrContents readMultilayerExr(const std::string& path) {
    ExrContents contents;
    checkExrBeforeReading(path);
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
