// How passes become a multilayer float EXR through OpenEXR's own API, and how one is read back.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/exr_file.h"

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
        if (p.pass.empty() || p.pass.find('.') != std::string::npos)
            bad("pass name '" + p.pass + "' is empty or has a dot");
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

void writeExrNow(const std::string& file, const std::string& shownPath, const std::string& viewLayer,
                 const std::vector<ExrPassRef>& passes, const std::string& methods) {
    const int w = passes.front().image->width, h = passes.front().image->height;
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.insert("Software", Imf::StringAttribute("softshadow " SS_VERSION));
    if (!methods.empty()) header.insert(kExrMethodsAttribute, Imf::StringAttribute(methods));
    Imf::FrameBuffer frame;
    for (const ExrPassRef& p : passes) {
        const std::string name = channelName(viewLayer, p.pass);
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        // Each pass is read in place from its own rows: no interleaved copy.
        char* base = reinterpret_cast<char*>(const_cast<float*>(p.image->pixels.data()));
        frame.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
    }
    try {
        Imf::OutputFile out(file.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(h);
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

void writeMultilayerExr(const std::string& path, const std::string& viewLayer,
                        const std::vector<ExrPassRef>& passes, const std::string& methods) {
    checkPasses(path, viewLayer, passes);
    writeAtomically(path, [&](const std::string& temp) { writeExrNow(temp, path, viewLayer, passes, methods); });
}

const ExrPass* ExrContents::find(const std::string& pass) const {
    for (const ExrPass& p : passes)
        if (p.pass == pass) return &p;
    return nullptr;
}

ExrContents readMultilayerExr(const std::string& path) {
    ExrContents contents;
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
    } catch (const std::exception& e) {
        fail(SS_ERROR_IO, "cannot read EXR '" + path + "': " + e.what());
    }
    return contents;
}

}  // namespace ss
