// How two visibility images are compared: the error numbers `softshadow compare` and every
// method's quality test report.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <string>

#include "core/image.h"
#include "core/visibility_classes.h"

namespace ss {

struct Metrics {
    size_t pixels = 0;      // pixels compared (inside the mask)
    double rmse = 0.0;      // sqrt(mean((a - b)^2))
    double meanAbs = 0.0;   // mean |a - b|
    double p99Abs = 0.0;    // 99th percentile of |a - b| (nearest rank: sorted[ceil(0.99 n) - 1])
    double maxAbs = 0.0;    // largest |a - b|
    double umbraIoU = 1.0;  // |A∩B| / |A∪B| of {V < 0.05}; two empty sets give 1
    double litIoU = 1.0;    // the same for {V > 0.95}

    std::string toJson() const;  // {"pixels":..,"rmse":..,"mean":..,"p99":..,"max":..,"umbra_iou":..,"lit_iou":..}
    std::string toString() const;  // one line for test failure messages
};

// Compares a and b (same size, else ss::Error SS_ERROR_INVALID_ARGUMENT) over the pixels where
// mask > 0.5 (mask: same size, or null for every pixel). No pixel in the mask gives zero errors
// and IoU 1. Non-finite pixels count as an error of 1 so they can never hide.
Metrics compareVisibility(const Image& a, const Image& b, const Image* mask = nullptr);

}  // namespace ss
