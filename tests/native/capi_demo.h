// How the C API tests open examples/scenes/demo.json at a test size with a context of their own.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <gtest/gtest.h>

#include "softshadow/softshadow.h"

namespace test {

struct CapiDemo {
    ss_scene* scene = nullptr;
    ss_context* context = nullptr;
    CapiDemo(int32_t width, int32_t height) {
        EXPECT_EQ(ss_scene_load(SS_SOURCE_DIR "/examples/scenes/demo.json", &scene), SS_OK)
            << ss_last_error();
        ss_camera_desc cam;
        EXPECT_EQ(ss_scene_get_camera(scene, &cam), SS_OK);
        cam.width = width, cam.height = height;
        EXPECT_EQ(ss_scene_set_camera(scene, &cam), SS_OK);
        EXPECT_EQ(ss_context_create(SS_BACKEND_AUTO, &context), SS_OK) << ss_last_error();
    }
    ~CapiDemo() {
        ss_context_destroy(context);
        ss_scene_destroy(scene);
    }
    CapiDemo(const CapiDemo&) = delete;
    CapiDemo& operator=(const CapiDemo&) = delete;
};

}  // namespace test
