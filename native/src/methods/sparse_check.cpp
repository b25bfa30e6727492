// How the sparse exact check is placed over the image and scored against a method's layers.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sparse_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "reference/adaptive_sampling.h"
#include "reference/render_reference.h"
#include "reference/sample_sequence.h"

namespace ss {

size_t SparseCheck::maskedPixels() const {
    return size_t(std::count_if(truth.begin(), truth.end(), [](const PixelVisibility& p) { return p.inMask; }));
}

int sparseCheckDefaultPixels(int width, int height) {
    const long long pixels = (long long)std::max(width, 0) * (long long)std::max(height, 0);
    return int(std::clamp(pixels / 16, 4096LL, 65536LL));
}

std::vector<std::pair<int, int>> sparseCheckPixels(int width, int height, int pixelCount, uint32_t seed) {
    std::vector<std::pair<int, int>> pixels;
    if (width <= 0 || height <= 0 || pixelCount <= 0) return pixels;
    if (size_t(pixelCount) >= size_t(width) * size_t(height)) {
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) pixels.emplace_back(x, y);
        return pixels;
    }
    // Square cells of the size that gives about pixelCount of them.
    const double side = std::sqrt(double(width) * double(height) / double(pixelCount));
    const int cols = std::max(1, int(std::lround(width / side))), rows = std::max(1, int(std::lround(height / side)));
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const int x0 = c * width / cols, x1 = (c + 1) * width / cols;
            const int y0 = r * height / rows, y1 = (r + 1) * height / rows;
            if (x1 <= x0 || y1 <= y0) continue;
            const uint32_t h = hashU32(seed ^ hashU32(uint32_t(r * cols + c) * 2654435761u));
            pixels.emplace_back(x0 + int(h % uint32_t(x1 - x0)), y0 + int(hashU32(h) % uint32_t(y1 - y0)));
        }
    return pixels;
}

SparseCheck runSparseCheck(const TraceScene& trace, const Scene& scene, int lightIndex, int pixelCount,
                           int samples, uint32_t seed) {
    const Camera& camera = scene.camera();
    SparseCheck check;
    AdaptiveSampling adaptive;
    adaptive.maxSamples = samples > 0 ? samples : kReferenceDefaultSamples;
    adaptive.minSamples = std::min(adaptive.minSamples, adaptive.maxSamples);
    check.truth = tracePixels(trace, scene, lightIndex, sparseCheckPixels(camera.width, camera.height, pixelCount, seed),
                              adaptive.maxSamples, seed, &adaptive);
    return check;
}

double checkedLowerBound(const SparseCheck& check,
                         const std::function<double(const PixelVisibility&)>& leastError) {
    double sum = 0.0;
    size_t n = 0;
    for (const PixelVisibility& p : check.truth) {
        if (!p.inMask) continue;
        ++n;
        const double d = leastError(p);
        sum += d * d;
    }
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

double estimatedRmse(const SparseCheck& check, const Layers& layers, const Image* traced, double tracedRmse) {
    const Image* v = layers.find("V");
    if (!v) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0.0;
    size_t n = 0;
    for (const PixelVisibility& p : check.truth) {
        if (!p.inMask) continue;
        ++n;
        if (traced && traced->at(p.x, p.y) != 0.0f) continue;
        const float value = v->at(p.x, p.y);
        const double d = std::isfinite(value) ? double(value) - double(p.visibility) : 1.0;
        sum += d * d;
    }
    if (!n) return std::numeric_limits<double>::quiet_NaN();
    return std::sqrt(sum / double(n) + (traced ? tracedRmse * tracedRmse : 0.0));
}

}  // namespace ss
