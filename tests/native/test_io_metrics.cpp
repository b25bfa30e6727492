// Whether compareVisibility gives the known RMSE, mean, p99 and IoU values on hand-made images.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/metrics.h"

namespace ss {
namespace {

// Every expected value below is computed by hand from a handful of pixel values, so the
// tolerance only absorbs double rounding (1e-12) except where float pixels are involved (1e-6).

TEST(IoMetrics, IdenticalImagesHaveNoError) {
    Image a(7, 5, 0.3f);
    a.at(2, 3) = 0.0f;
    a.at(6, 4) = 1.0f;
    Metrics m = compareVisibility(a, a, nullptr);
    EXPECT_EQ(m.pixels, 35u);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.meanAbs, 0.0);
    EXPECT_EQ(m.p99Abs, 0.0);
    EXPECT_EQ(m.umbraIoU, 1.0);
    EXPECT_EQ(m.litIoU, 1.0);
}

TEST(IoMetrics, ErrorsOfTenPixelsOutOfHundred) {
    // 100 pixels, 10 of them off by 0.25 (exact in binary): rmse = sqrt(10 * 0.0625 / 100),
    // mean = 2.5 / 100, p99 = the 99th of 100 sorted errors = 0.25.
    Image a(10, 10, 0.5f), b(10, 10, 0.5f);
    for (int x = 0; x < 10; ++x) b.at(x, 4) = 0.75f;
    Metrics m = compareVisibility(a, b, nullptr);
    EXPECT_EQ(m.pixels, 100u);
    EXPECT_NEAR(m.rmse, std::sqrt(0.00625), 1e-12);
    EXPECT_NEAR(m.meanAbs, 0.025, 1e-12);
    EXPECT_EQ(m.p99Abs, 0.25);
    EXPECT_EQ(m.maxAbs, 0.25);
}

TEST(IoMetrics, P99IgnoresASingleOutlierInHundred) {
    // Nearest rank: p99 of 100 values is sorted[98]; one error of 0.5 sits at sorted[99].
    Image a(10, 10, 0.5f), b = a;
    b.at(3, 3) = 1.0f;
    Metrics m = compareVisibility(a, b, nullptr);
    EXPECT_EQ(m.p99Abs, 0.0);
    EXPECT_EQ(m.maxAbs, 0.5);
    EXPECT_NEAR(m.meanAbs, 0.005, 1e-12);
}

TEST(IoMetrics, UmbraAndLitIoUOfShiftedEdges) {
    // a: columns 0-4 umbra (0), 5-9 lit (1). b: columns 0-5 umbra, 6-9 lit.
    // umbra: |A∩B| = 5 columns, |A∪B| = 6 -> 5/6. lit: 4 / 5.
    Image a(10, 4, 1.0f), b(10, 4, 1.0f);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 5; ++x) a.at(x, y) = 0.0f;
        for (int x = 0; x < 6; ++x) b.at(x, y) = 0.0f;
    }
    Metrics m = compareVisibility(a, b, nullptr);
    EXPECT_NEAR(m.umbraIoU, 5.0 / 6.0, 1e-12);
    EXPECT_NEAR(m.litIoU, 4.0 / 5.0, 1e-12);
    EXPECT_NEAR(m.meanAbs, 0.1, 1e-12);  // one column of 10 differs by 1
}

TEST(IoMetrics, ThresholdsAreStrict) {
    // V = 0.05 is not umbra and V = 0.95 is not lit (V < 0.05, V > 0.95), so each image's
    // sets are empty on one side: IoU of two empty sets is 1, of an empty and a full set 0.
    Image a(2, 1), b(2, 1);
    a.pixels = {0.05f, 0.95f};
    b.pixels = {0.0499f, 0.9501f};
    Metrics m = compareVisibility(a, b, nullptr);
    EXPECT_EQ(m.umbraIoU, 0.0);
    EXPECT_EQ(m.litIoU, 0.0);
    Metrics same = compareVisibility(a, a, nullptr);
    EXPECT_EQ(same.umbraIoU, 1.0);
    EXPECT_EQ(same.litIoU, 1.0);
}

TEST(IoMetrics, MaskSelectsPixels) {
    // Same images as the shifted-edge test, masked to columns 0-4 where they agree.
    Image a(10, 4, 1.0f), b(10, 4, 1.0f), mask(10, 4, 0.0f);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 5; ++x) a.at(x, y) = 0.0f, mask.at(x, y) = 1.0f;
        for (int x = 0; x < 6; ++x) b.at(x, y) = 0.0f;
    }
    Metrics m = compareVisibility(a, b, &mask);
    EXPECT_EQ(m.pixels, 20u);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.umbraIoU, 1.0);
    EXPECT_EQ(m.litIoU, 1.0);  // no lit pixel in either image inside the mask
}

TEST(IoMetrics, EmptyMaskGivesZeroErrorAndIoUOne) {
    Image a(3, 3, 0.0f), b(3, 3, 1.0f), mask(3, 3, 0.0f);
    Metrics m = compareVisibility(a, b, &mask);
    EXPECT_EQ(m.pixels, 0u);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.umbraIoU, 1.0);
    EXPECT_EQ(m.litIoU, 1.0);
}

TEST(IoMetrics, NonFinitePixelsCountAsFullError) {
    Image a(2, 1, 0.5f), b(2, 1, 0.5f);
    b.pixels[1] = std::numeric_limits<float>::quiet_NaN();
    Metrics m = compareVisibility(a, b, nullptr);
    EXPECT_EQ(m.maxAbs, 1.0);
    EXPECT_NEAR(m.meanAbs, 0.5, 1e-12);
}

TEST(IoMetrics, SizeMismatchIsAnError) {
    Image a(4, 4), b(4, 5), mask(5, 4);
    try {
        compareVisibility(a, b, nullptr);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(e.what()).find("4x4 and 4x5"), std::string::npos) << e.what();
    }
    EXPECT_THROW(compareVisibility(a, a, &mask), Error);
}

TEST(IoMetrics, JsonHasEveryField) {
    Image a(2, 2, 0.0f), b(2, 2, 0.5f);
    std::string j = compareVisibility(a, b, nullptr).toJson();
    for (const char* key : {"\"pixels\":4", "\"rmse\":0.5", "\"mean\":0.5", "\"p99\":0.5", "\"umbra_iou\":0",
                            "\"lit_iou\":1"})
        EXPECT_NE(j.find(key), std::string::npos) << key << " in " << j;
}

}  // namespace
}  // namespace ss
