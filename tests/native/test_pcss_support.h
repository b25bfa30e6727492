// How the pcss and penumbra_map tests render a method and the reference on the shared scenes.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "io/metrics.h"
#include "io/png_preview.h"
#include "methods/method.h"
#include "renderer/renderer.h"
#include "test_scenes.h"

namespace ss::test {

// One renderer for a whole test binary run: starting GL costs ~20 ms per thread and context.
inline Renderer& sharedRenderer() {
    // Never destroyed: its render thread is joined by shutdownRenderThreads() at exit, and a
    // static Renderer would be torn down after the thread registry it relies on.
    static Renderer* r = new Renderer(SS_BACKEND_AUTO);
    return *r;
}

inline Layers renderWith(const Scene& scene, const std::string& method,
                         const std::map<std::string, std::string>& options = {}, int samples = 0,
                         int light = 0) {
    RenderSettings s;
    s.options = options;
    s.samples = samples;
    return sharedRenderer().render(scene, light, method, s, nullptr);
}

// renderWith, refined (RenderSettings::refine: what a final render asks for).
inline Layers refinedWith(const Scene& scene, const std::string& method,
                          const std::map<std::string, std::string>& options = {}, int samples = 0) {
    RenderSettings s;
    s.options = options;
    s.samples = samples;
    s.refine = true;
    return sharedRenderer().render(scene, 0, method, s, nullptr);
}

// Expects rendering `method` with `options` to fail with SS_ERROR_INVALID_ARGUMENT and a message
// naming `setting`.
inline void expectSettingRefused(const Scene& scene, const std::string& method,
                                 const std::map<std::string, std::string>& options, const std::string& setting) {
    try {
        renderWith(scene, method, options);
        ADD_FAILURE() << method << ": a bad " << setting << " was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(e.what()).find(setting), std::string::npos) << e.what();
    }
}

// The reference at 256 samples: its own noise (sd <= 0.5/sqrt(256) = 0.03 per pixel, less
// with stratification) is small next to every bound the quality tests set.
inline Layers renderReference(const Scene& scene) {
    return renderWith(scene, "reference", {}, quickTests() ? 64 : 256);
}

inline Metrics compareToReference(const Layers& method, const Layers& reference) {
    return compareVisibility(*method.find("V"), *reference.find("V"), reference.find("mask"));
}

// With SS_TEST_DUMP=dir set, writes the image as dir/name.png to look at a failure.
inline void dumpPng(const std::string& name, const Image& image) {
    const char* dir = std::getenv("SS_TEST_DUMP");
    if (dir && *dir) writePngPreview(std::string(dir) + "/" + name + ".png", image);
}

// The shared scenes as the pcss and penumbra_map tests view them: the light moved sideways so
// each shadow falls beside its occluder (seen, not hidden under it), the camera zoomed in on it.
inline SceneParams softSceneParams() {
    SceneParams p;
    p.lightShift = {1.2f, 0.8f};
    p.cameraZoom = 1.6f;
    return p;
}

// Pixels inside the mask where a and b differ by more than `by`.
inline size_t countDiffering(const Layers& a, const Layers& b, float by) {
    const Image& va = *a.find("V");
    const Image& vb = *b.find("V");
    const Image& m = *a.find("mask");
    size_t n = 0;
    for (size_t i = 0; i < va.pixels.size(); ++i)
        if (m.pixels[i] > 0.5f && std::abs(va.pixels[i] - vb.pixels[i]) > by) ++n;
    return n;
}

inline size_t maskPixels(const Layers& a) {
    size_t n = 0;
    for (float x : a.find("mask")->pixels) n += x > 0.5f;
    return n;
}

// Count of pixels with mask set whose V is below `below`.
inline size_t countBelow(const Layers& layers, float below) {
    const Image& v = *layers.find("V");
    const Image& m = *layers.find("mask");
    size_t n = 0;
    for (size_t i = 0; i < v.pixels.size(); ++i)
        if (m.pixels[i] > 0.5f && v.pixels[i] < below) ++n;
    return n;
}

// Sum over the mask of (1 - V): the total amount of shadow, in pixels.
inline double shadowAmount(const Layers& layers) {
    const Image& v = *layers.find("V");
    const Image& m = *layers.find("mask");
    double s = 0.0;
    for (size_t i = 0; i < v.pixels.size(); ++i)
        if (m.pixels[i] > 0.5f) s += 1.0 - v.pixels[i];
    return s;
}

// Pixels strictly between fully shadowed and fully lit (the method's own penumbra).
inline size_t penumbraPixels(const Layers& layers, float eps = 0.02f) {
    const Image& v = *layers.find("V");
    const Image& m = *layers.find("mask");
    size_t n = 0;
    for (size_t i = 0; i < v.pixels.size(); ++i)
        if (m.pixels[i] > 0.5f && v.pixels[i] > eps && v.pixels[i] < 1.0f - eps) ++n;
    return n;
}

// Every layer finite; V, mask, umbra, penumbra inside [0, 1]; V = 1 outside the mask.
inline std::string checkLayersSane(const Layers& layers) {
    const Image& mask = *layers.find("mask");
    for (const auto& [name, img] : layers.items) {
        bool unit = name == "V" || name == "mask" || name == "umbra" || name == "penumbra" ||
                    name == "penumbra_map";
        for (size_t i = 0; i < img.pixels.size(); ++i) {
            float x = img.pixels[i];
            if (!std::isfinite(x)) return "layer " + name + " has a non-finite pixel " + std::to_string(i);
            if (unit && (x < 0.0f || x > 1.0f))
                return "layer " + name + " pixel " + std::to_string(i) + " = " + std::to_string(x);
            if (name == "V" && mask.pixels[i] <= 0.5f && x != 1.0f)
                return "V is " + std::to_string(x) + " outside the mask at " + std::to_string(i);
        }
    }
    return "";
}

}  // namespace ss::test
