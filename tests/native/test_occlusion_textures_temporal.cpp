// How much does occlusion_textures flicker when things move: the paper's two temporal limits
// (flicker under vertical motion as the slice weights change, blocky mipmaps when animated),
// measured frame to frame against the reference's own change.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/light.h"
#include "softshadow/softshadow.h"
#include "test_pcss_support.h"

namespace ss::test {
namespace {

// A plate over the ground under a square light; a small box far off to the side, just below the
// light, pins the slices' top so the slice planes stay put while the plate moves through them.
Scene plateAt(glm::vec3 offset, float lightSize) {
    Scene s;
    s.addMesh(makeGround(8.0f, 0.0f, SS_MESH_CAST | SS_MESH_RECEIVE));
    s.addMesh(makeBox({7.0f, 7.0f, 3.4f}, {7.2f, 7.2f, 3.5f}, SS_MESH_CAST));
    s.addMesh(makeBox(glm::vec3(-0.6f, -0.6f, -0.02f) + offset, glm::vec3(0.6f, 0.6f, 0.02f) + offset, SS_MESH_CAST));
    Light light = makeDiskLight({0.0f, 0.0f, 4.0f}, lightSize);
    light.type = LightType::Square;
    s.addLight(light);
    s.setCamera(makeTopCamera());
    return s;
}

// Per frame-to-frame step, over the pixels the penumbra crosses during the motion (reference
// between 0.02 and 0.98 in some frame): the mean |dV| for the method and the reference, and
// the mean |dV_method - dV_reference| (the change the motion does not explain). And the
// roughness: the mean |V(t+1) - 2 V(t) + V(t-1)| per pixel and step, 0 for a shadow that moves
// steadily, large where it holds still and then jumps.
struct Steps {
    std::vector<double> method, reference, excess;
    double roughness = 0.0, referenceRoughness = 0.0;
    size_t pixels = 0;
    double meanMethod() const { return mean(method); }
    double meanReference() const { return mean(reference); }
    double meanExcess() const { return mean(excess); }
    // Steps where the shadow held still (under a tenth of the reference's change) while the
    // occluder moved.
    size_t stalls() const {
        size_t n = 0;
        for (size_t i = 0; i < method.size(); ++i) n += method[i] < 0.1 * reference[i];
        return n;
    }
    // The largest step over the mean step: 1 for a steady change, large for jumps.
    double spike() const { return *std::max_element(method.begin(), method.end()) / std::max(mean(method), 1e-12); }
    static double mean(const std::vector<double>& v) {
        double s = 0.0;
        for (double x : v) s += x;
        return v.empty() ? 0.0 : s / double(v.size());
    }
    bool finite() const {
        for (const auto* v : {&method, &reference, &excess})
            for (double x : *v)
                if (!std::isfinite(x)) return false;
        return !method.empty() && std::isfinite(roughness) && std::isfinite(referenceRoughness);
    }
};

struct Animation {
    std::vector<Image> method, reference;
    Image mask;  // the receiver (the ground does not move)
};

// Renders the method at each offset; the reference too, unless `sameMotion` already has it.
Animation animate(const std::vector<glm::vec3>& offsets, float lightSize,
                  const std::map<std::string, std::string>& options, const Animation* sameMotion) {
    Animation a;
    if (sameMotion) a.reference = sameMotion->reference, a.mask = sameMotion->mask;
    for (size_t f = 0; f < offsets.size(); ++f) {
        Scene scene = plateAt(offsets[f], lightSize);
        Layers ot = renderWith(scene, "occlusion_textures", options);
        a.method.push_back(*ot.find("V"));
        if (sameMotion) continue;
        Layers ref = renderReference(scene);
        a.reference.push_back(*ref.find("V"));
        a.mask = *ref.find("mask");
    }
    return a;
}

Steps steps(const Animation& a) {
    Steps s;
    std::vector<size_t> crossed;
    for (size_t i = 0; i < a.mask.pixels.size(); ++i) {
        if (a.mask.pixels[i] < 0.5f) continue;
        bool penumbra = false;
        for (const Image& r : a.reference) penumbra = penumbra || (r.pixels[i] > 0.02f && r.pixels[i] < 0.98f);
        if (penumbra) crossed.push_back(i);
    }
    s.pixels = crossed.size();
    const double n = double(std::max<size_t>(crossed.size(), 1));
    for (size_t f = 1; f < a.method.size(); ++f) {
        double m = 0.0, r = 0.0, e = 0.0;
        for (size_t i : crossed) {
            double dm = double(a.method[f].pixels[i]) - a.method[f - 1].pixels[i];
            double dr = double(a.reference[f].pixels[i]) - a.reference[f - 1].pixels[i];
            m += std::abs(dm), r += std::abs(dr), e += std::abs(dm - dr);
        }
        s.method.push_back(m / n);
        s.reference.push_back(r / n);
        s.excess.push_back(e / n);
    }
    auto second = [&](const std::vector<Image>& v) {
        double sum = 0.0;
        for (size_t f = 1; f + 1 < v.size(); ++f)
            for (size_t i : crossed)
                sum += std::abs(double(v[f + 1].pixels[i]) - 2.0 * v[f].pixels[i] + v[f - 1].pixels[i]);
        return sum / (n * double(std::max<size_t>(v.size() - 2, 1)));
    };
    s.roughness = second(a.method);
    s.referenceRoughness = second(a.reference);
    return s;
}

// One image row (through the plate's shadow) per frame, stacked top to bottom and 3 pixels
// tall: a space-time picture where a steady motion draws smooth slopes and flicker draws steps.
Image spaceTime(const std::vector<Image>& frames, int row) {
    Image out(frames[0].width, int(frames.size()) * 3);
    for (size_t f = 0; f < frames.size(); ++f)
        for (int k = 0; k < 3; ++k)
            for (int x = 0; x < out.width; ++x) out.at(x, int(f) * 3 + k) = frames[f].at(x, row);
    return out;
}

// Side by side with a 2-pixel white gap.
Image besideEachOther(const std::vector<Image>& parts) {
    int w = 0;
    for (const Image& p : parts) w += p.width + 2;
    Image out(w - 2, parts[0].height, 1.0f);
    int x0 = 0;
    for (const Image& p : parts) {
        for (int y = 0; y < p.height; ++y)
            for (int x = 0; x < p.width; ++x) out.at(x0 + x, y) = p.at(x, y);
        x0 += p.width + 2;
    }
    return out;
}

void print(const char* what, const Steps& s) {
    std::printf("[occlusion_textures] %s, %zu px crossed by the penumbra: mean |dV| per step %.4f (reference %.4f), "
                "mean |dV - dV_ref| %.4f, largest step / mean step %.2f, %zu of %zu steps stalled, roughness %.4f "
                "(reference %.4f)\n  steps (method/reference):",
                what, s.pixels, s.meanMethod(), s.meanReference(), s.meanExcess(), s.spike(), s.stalls(),
                s.method.size(), s.roughness, s.referenceRoughness);
    for (size_t i = 0; i < s.method.size(); ++i) std::printf(" %.4f/%.4f", s.method[i], s.reference[i]);
    std::printf("\n");
}

// Limit 1 of the paper's conclusion: "a slight flickering can occur for vertical movements as
// the weighting for the closest slice changes". The plate rises from 0.9 to 1.9 in 16 steps of
// 1/16 m across three slice planes (8 slices, 0.44 m thick); the reference's shadow changes
// steadily, the method's steps follow the slice weights.
TEST(OcclusionTexturesTemporal, FlickerUnderVerticalMotion) {
    std::vector<glm::vec3> offsets;
    for (int f = 0; f <= 16; ++f) offsets.push_back({0.0f, 0.0f, 0.9f + float(f) / 16.0f});
    Animation a = animate(offsets, 1.0f, {}, nullptr);
    Steps s = steps(a);
    print("vertical motion, sat", s);
    ASSERT_TRUE(s.finite());
    // Measured (1,938 px): the shadow holds still while the plate stays inside a slice and jumps
    // when it crosses a plane (steps 0.070, 0.044, 0.081, 0.109 against the reference's steady
    // 0.010-0.036; 12 of 16 steps stalled); roughness 0.040 against the reference's 0.006.
    // Bounded, and the paper's limit present (a change that removes it must update
    // docs/methods/occlusion_textures.md).
    EXPECT_GT(s.meanMethod(), 0.5 * s.meanReference());
    EXPECT_LT(s.meanMethod(), 2.0 * s.meanReference());
    EXPECT_LT(s.spike(), 10.0);
    EXPECT_LT(s.roughness, 0.1);
    EXPECT_GT(s.roughness, 3.0 * s.referenceRoughness);
    EXPECT_GE(s.stalls(), 6u);
    const int row = a.method[0].height / 2;
    dumpPng("occlusion_textures_vertical_space_time",
            besideEachOther({spaceTime(a.method, row), spaceTime(a.reference, row)}));
}

// Limit 2 (section 3.2): mipmaps are "blocky" when animated, the dyadic levels joining
// neighbouring texels only high in the pyramid, so a slight shift of the occluder changes the
// filtered value by a lot. The plate slides sideways 1/64 m per frame (about two thirds of a
// texel of the 512² occlusion textures at its slice), under a 1 m light and, for kernels high in
// the pyramid, a 2.5 m one; each filter's frame-to-frame change is compared with the reference's.
TEST(OcclusionTexturesTemporal, BlockyMipmapsUnderSidewaysMotion) {
    struct Case {
        float lightSize, height;
    };
    for (Case c : {Case{1.0f, 1.2f}, Case{2.5f, 2.0f}}) {
        std::vector<glm::vec3> offsets;
        for (int f = 0; f <= 16; ++f) offsets.push_back({float(f) / 64.0f, 0.0f, c.height});
        Animation sat = animate(offsets, c.lightSize, {{"filter", "sat"}}, nullptr);
        Animation nbuffer = animate(offsets, c.lightSize, {{"filter", "nbuffer"}}, &sat);
        Animation mipmap = animate(offsets, c.lightSize, {{"filter", "mipmap"}}, &sat);
        Steps ss = steps(sat), sn = steps(nbuffer), sm = steps(mipmap);
        char what[96];
        for (auto [name, s] : {std::pair{"sat", &ss}, {"nbuffer", &sn}, {"mipmap", &sm}}) {
            std::snprintf(what, sizeof what, "sideways motion, light %.1f m, plate at %.1f m, %s", c.lightSize,
                          c.height, name);
            print(what, *s);
            ASSERT_TRUE(s->finite());
            EXPECT_GT(s->meanMethod(), 0.3 * s->meanReference());
            EXPECT_LT(s->meanMethod(), 3.0 * s->meanReference());
            EXPECT_LT(s->roughness, 0.1);
            // The occluder is rasterised in binary texels, so the shadow moves in texel steps
            // whatever the filter: it holds still in some steps (measured 5 of 16; roughness
            // 2.7-3.4x the reference's, whose own sampling noise enters that ratio).
            EXPECT_GE(s->stalls(), 3u);
        }
        // Not reproduced: the mipmap lookup here (trilinear, probes along the kernel's long
        // side) is no rougher than the exact SAT (measured 0.040 vs 0.046 and 0.010 vs 0.012).
        EXPECT_LT(sm.roughness, 1.1 * ss.roughness);
        const int row = sat.method[0].height / 2;
        std::snprintf(what, sizeof what, "occlusion_textures_sideways_space_time_%.1f", c.lightSize);
        dumpPng(what, besideEachOther({spaceTime(mipmap.method, row), spaceTime(nbuffer.method, row),
                                       spaceTime(sat.method, row), spaceTime(sat.reference, row)}));
    }
}

}  // namespace
}  // namespace ss::test
