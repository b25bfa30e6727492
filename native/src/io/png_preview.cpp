// How a float pass is quantised to an 8-bit grayscale PNG through OpenImageIO.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/png_preview.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "core/error.h"
#include "io/atomic_file.h"

namespace ss {

void writePngPreview(const std::string& path, const Image& image) { stagePngPreview(path, image).commit(); }

StagedFile stagePngPreview(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != size_t(image.width) * image.height)
        fail(SS_ERROR_INVALID_ARGUMENT, "cannot write PNG '" + path + "': the image has no pixels");
    std::vector<unsigned char> bytes(image.pixels.size());
    for (size_t i = 0; i < bytes.size(); ++i) {
        float v = image.pixels[i];
        // Visibility is linear in [0,1]; a preview shows it as is (no display transform), NaN black.
        v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
        bytes[i] = (unsigned char)std::lround(v * 255.0f);
    }
    return StagedFile(path, [&](const std::string& temp) {
        OIIO::ImageSpec spec(image.width, image.height, 1, OIIO::TypeDesc::UINT8);
        auto out = OIIO::ImageOutput::create("png");
        if (!out) fail(SS_ERROR_IO, "cannot write PNG '" + path + "': " + OIIO::geterror());
        if (!out->open(temp, spec))
            fail(SS_ERROR_IO, "cannot write PNG '" + path + "': " + out->geterror());
        bool ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
        std::string err = ok ? std::string() : out->geterror();
        if (!out->close() && ok) ok = false, err = out->geterror();
        if (!ok) fail(SS_ERROR_IO, "cannot write PNG '" + path + "': " + err);
    });
}

}  // namespace ss
