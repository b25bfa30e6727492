// Which EGL device renders: Mesa's device list, SOFTSHADOW_EGL_DEVICE, and what `info` says.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "gl/context.h"
#include "renderer/renderer.h"
#include "test_scenes.h"

namespace ss {
namespace {

// Sets SOFTSHADOW_EGL_DEVICE for one test and restores it after.
struct DeviceVariable {
    explicit DeviceVariable(const std::string& value) {
        const char* old = std::getenv(gl::kEglDeviceVariable);
        had = old != nullptr;
        if (had) previous = old;
        setenv(gl::kEglDeviceVariable, value.c_str(), 1);
    }
    ~DeviceVariable() {
        if (had) setenv(gl::kEglDeviceVariable, previous.c_str(), 1);
        else unsetenv(gl::kEglDeviceVariable);
    }
    bool had = false;
    std::string previous;
};

int softwareDevice() {
    for (const gl::EglDevice& d : gl::eglDevices())
        if (d.software) return d.index;
    return -1;
}

nlohmann::json infoWith(const std::string& variable) {
    DeviceVariable v(variable);
    Renderer renderer(SS_BACKEND_EGL);
    return nlohmann::json::parse(renderer.info());
}

TEST(EglDevices, MesaListsItsSoftwareDevice) {
    ASSERT_GE(softwareDevice(), 0) << "Mesa's EGL lists llvmpipe as a software device";
    for (const gl::EglDevice& d : gl::eglDevices()) EXPECT_NE(d.describe().find("device "), std::string::npos);
}

TEST(EglDevices, AutoPrefersAHardwareDeviceElseSurfaceless) {
    bool hardware = false;
    for (const gl::EglDevice& d : gl::eglDevices()) hardware = hardware || !d.software;
    nlohmann::json info = infoWith("auto");
    ASSERT_TRUE(info.contains("device"));
    if (hardware)
        EXPECT_EQ(info["device"].get<std::string>().find("software"), std::string::npos) << info.dump();
    else
        EXPECT_EQ(info["device"], "surfaceless") << info.dump();
    EXPECT_EQ(info["egl_devices"].size(), gl::eglDevices().size());
}

TEST(EglDevices, TheVariableChoosesADeviceThatRenders) {
    int index = softwareDevice();
    ASSERT_GE(index, 0);
    DeviceVariable v(std::to_string(index));
    Renderer renderer(SS_BACKEND_EGL);
    nlohmann::json info = nlohmann::json::parse(renderer.info());
    EXPECT_EQ(info["device"], "device " + std::to_string(index) + " (software)") << info.dump();
    Scene scene;
    scene.addMesh(test::makeGround(4.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addMesh(test::makeBox({-0.5f, -0.5f, 0.6f}, {0.5f, 0.5f, 1.0f}, SS_MESH_CAST | SS_MESH_RECEIVE));
    scene.addLight(test::makeDiskLight({1.5f, 0.0f, 4.0f}, 0.5f, "A"));
    scene.setCamera(test::makeTopCamera(64, 48));
    Layers onDevice = renderer.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    const auto& v0 = onDevice.find("V")->pixels;
    // The box's shadow and the lit ground are both in the picture.
    EXPECT_LT(*std::min_element(v0.begin(), v0.end()), 0.05f);
    EXPECT_GT(*std::max_element(v0.begin(), v0.end()), 0.95f);

    DeviceVariable surfaceless("surfaceless");
    Renderer other(SS_BACKEND_EGL);
    EXPECT_EQ(nlohmann::json::parse(other.info())["device"], "surfaceless");
    Layers onSurfaceless = other.render(scene, 0, "shadow_map", RenderSettings{}, nullptr);
    EXPECT_EQ(onSurfaceless.find("V")->pixels, v0);  // both are llvmpipe here
}

TEST(EglDevices, AnUnknownChoiceFailsNamingTheVariable) {
    DeviceVariable v("99");
    Renderer renderer(SS_BACKEND_EGL);
    try {
        renderer.info();
        FAIL() << "device 99 was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_GL);
        EXPECT_NE(std::string(e.what()).find("SOFTSHADOW_EGL_DEVICE='99'"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace ss
