// How passes become a multilayer float EXR through OpenImageIO, and how one is read back.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/exr_file.h"

#include <set>

#include <OpenImageIO/imageio.h>

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
    const int n = int(passes.size());
    OIIO::ImageSpec spec(w, h, n, OIIO::TypeDesc::FLOAT);
    spec.channelnames.clear();
    for (const ExrPassRef& p : passes) spec.channelnames.push_back(channelName(viewLayer, p.pass));
    spec.alpha_channel = -1;
    spec.attribute("compression", "zip");
    spec.attribute("Software", "softshadow " SS_VERSION);
    if (!methods.empty()) spec.attribute(kExrMethodsAttribute, methods);

    std::vector<float> interleaved(size_t(w) * h * n);
    for (int c = 0; c < n; ++c) {
        const std::vector<float>& src = passes[c].image->pixels;
        for (size_t i = 0; i < src.size(); ++i) interleaved[i * n + c] = src[i];
    }

    auto out = OIIO::ImageOutput::create("openexr");
    if (!out) fail(SS_ERROR_IO, "cannot write EXR '" + shownPath + "': " + OIIO::geterror());
    if (!out->open(file, spec))
        fail(SS_ERROR_IO, "cannot write EXR '" + shownPath + "': " + out->geterror());
    bool ok = out->write_image(OIIO::TypeDesc::FLOAT, interleaved.data());
    std::string err = ok ? std::string() : out->geterror();
    if (!out->close() && ok) {
        ok = false;
        err = out->geterror();
    }
    if (!ok) fail(SS_ERROR_IO, "cannot write EXR '" + shownPath + "': " + err);
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
    auto in = OIIO::ImageInput::open(path);
    if (!in) fail(SS_ERROR_IO, "cannot read EXR '" + path + "': " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    ExrContents contents;
    contents.width = spec.width;
    contents.height = spec.height;
    const int n = spec.nchannels;
    std::vector<float> interleaved(size_t(spec.width) * spec.height * n);
    if (!in->read_image(0, 0, 0, n, OIIO::TypeDesc::FLOAT, interleaved.data()))
        fail(SS_ERROR_IO, "cannot read EXR '" + path + "': " + in->geterror());
    for (int c = 0; c < n; ++c) {
        ExrPass p;
        const std::string& full = spec.channelnames[c];
        size_t last = full.rfind('.');
        if (last == std::string::npos) {
            p.pass = full;
        } else {
            p.channel = full.substr(last + 1);
            size_t prev = last == 0 ? std::string::npos : full.rfind('.', last - 1);
            if (prev == std::string::npos) {
                p.pass = full.substr(0, last);
            } else {
                p.layer = full.substr(0, prev);
                p.pass = full.substr(prev + 1, last - prev - 1);
            }
        }
        p.image = Image(spec.width, spec.height);
        for (size_t i = 0; i < p.image.pixels.size(); ++i) p.image.pixels[i] = interleaved[i * n + c];
        contents.passes.push_back(std::move(p));
    }
    in->close();
    return contents;
}

}  // namespace ss
