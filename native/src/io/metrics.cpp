// How the error numbers between two visibility images are computed over a mask.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/error.h"

namespace ss {

namespace {
std::string sizeText(const Image& img) {
    return std::to_string(img.width) + "x" + std::to_string(img.height);
}

struct SetCounts {
    size_t both = 0, either = 0;
    void add(bool a, bool b) {
        both += (a && b);
        either += (a || b);
    }
    double iou() const { return either == 0 ? 1.0 : double(both) / double(either); }
};
}  // namespace

Metrics compareVisibility(const Image& a, const Image& b, const Image* mask) {
    if (a.width != b.width || a.height != b.height)
        fail(SS_ERROR_INVALID_ARGUMENT,
             "cannot compare images of different sizes (" + sizeText(a) + " and " + sizeText(b) + ")");
    if (mask && (mask->width != a.width || mask->height != a.height))
        fail(SS_ERROR_INVALID_ARGUMENT,
             "mask is " + sizeText(*mask) + " but the images are " + sizeText(a));
    if (a.pixels.size() != size_t(a.width) * a.height || b.pixels.size() != a.pixels.size() ||
        (mask && mask->pixels.size() != a.pixels.size()))
        fail(SS_ERROR_INVALID_ARGUMENT, "an image's pixel buffer does not match its size");

    Metrics m;
    std::vector<float> errors;
    errors.reserve(a.pixels.size());
    double sumSq = 0.0, sumAbs = 0.0;
    SetCounts umbra, lit;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        if (mask && !(mask->pixels[i] > 0.5f)) continue;
        float va = a.pixels[i], vb = b.pixels[i];
        double e = (std::isfinite(va) && std::isfinite(vb)) ? std::abs(double(va) - double(vb)) : 1.0;
        errors.push_back(float(e));
        sumSq += e * e;
        sumAbs += e;
        m.maxAbs = std::max(m.maxAbs, e);
        umbra.add(isUmbra(va), isUmbra(vb));
        lit.add(isLit(va), isLit(vb));
    }
    m.pixels = errors.size();
    m.umbraIoU = umbra.iou();
    m.litIoU = lit.iou();
    if (m.pixels == 0) return m;
    m.rmse = std::sqrt(sumSq / double(m.pixels));
    m.meanAbs = sumAbs / double(m.pixels);
    size_t rank = size_t(std::ceil(0.99 * double(m.pixels)));
    size_t k = std::clamp<size_t>(rank, 1, m.pixels) - 1;
    std::nth_element(errors.begin(), errors.begin() + k, errors.end());
    m.p99Abs = errors[k];
    return m;
}

std::string Metrics::toJson() const {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "{\"pixels\":%zu,\"rmse\":%.9g,\"mean\":%.9g,\"p99\":%.9g,\"max\":%.9g,"
                  "\"umbra_iou\":%.9g,\"lit_iou\":%.9g}",
                  pixels, rmse, meanAbs, p99Abs, maxAbs, umbraIoU, litIoU);
    return buf;
}

std::string Metrics::toString() const {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "pixels=%zu rmse=%.5f mean=%.5f p99=%.5f max=%.5f umbra_iou=%.4f lit_iou=%.4f",
                  pixels, rmse, meanAbs, p99Abs, maxAbs, umbraIoU, litIoU);
    return buf;
}

}  // namespace ss
