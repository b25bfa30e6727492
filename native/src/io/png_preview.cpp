// How a float pass is quantised to an 8-bit grayscale PNG through stb_image_write.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/png_preview.h"

#include <algorithm>
#include <cmath>
#include <vector>

// stb_image_write is compiled here, static to this file, so the library exports none of it.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

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
        if (!stbi_write_png(temp.c_str(), image.width, image.height, 1, bytes.data(), image.width))
            fail(SS_ERROR_IO, "cannot write PNG '" + path + "'");
    });
}

std::string previewFileName(const std::string& pass) {
    std::string name = pass;
    for (char& c : name) {
        unsigned char u = (unsigned char)c;
        if (c == '/' || c == '\\' || u < 0x20 || u == 0x7F) c = '_';
    }
    if (!name.empty() && name[0] == '.') name[0] = '_';
    return name + ".png";
}

}  // namespace ss
