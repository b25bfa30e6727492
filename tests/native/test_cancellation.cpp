// Do the CPU stages (dbuffer's volumes, the sweep's light samples) stop when a render is cancelled?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <atomic>

#include <gtest/gtest.h>

#include "core/error.h"
#include "methods/dbuffer/geometry.h"
#include "methods/sweep/shadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

using test::statusOf;

TEST(Cancellation, DbufferVolumesStopWhenCancelled) {
    Scene scene = test::sceneConcave();
    std::atomic<bool> cancel{true};
    EXPECT_EQ(statusOf([&] { dbufferGeometry(scene, 0, scene.bounds(), &cancel); }), SS_ERROR_CANCELLED);
    cancel = false;
    EXPECT_EQ(statusOf([&] { dbufferGeometry(scene, 0, scene.bounds(), &cancel); }), SS_OK);
}

TEST(Cancellation, SweepSamplesStopWhenCancelled) {
    Scene scene = test::sceneBox();
    RenderSettings settings;
    std::atomic<bool> cancel{true};
    settings.cancel = &cancel;
    SweepOptions options = sweepOptions(settings);
    EXPECT_EQ(statusOf([&] { computeSweepShadow(scene, 0, options); }), SS_ERROR_CANCELLED);
    cancel = false;
    EXPECT_EQ(statusOf([&] { computeSweepShadow(scene, 0, options); }), SS_OK);
}

TEST(Cancellation, ReportStopsOnTheCancelFlagToo) {
    RenderSettings settings;
    std::atomic<bool> cancel{false};
    settings.cancel = &cancel;
    EXPECT_EQ(statusOf([&] { settings.report(0.5f, "stage"); }), SS_OK);
    cancel = true;
    EXPECT_EQ(statusOf([&] { settings.report(0.5f, "stage"); }), SS_ERROR_CANCELLED);
    EXPECT_EQ(statusOf([&] { settings.checkCancelled("stage"); }), SS_ERROR_CANCELLED);
}

}  // namespace
}  // namespace ss
