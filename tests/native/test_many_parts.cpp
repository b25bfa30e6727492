// Checks dbuffer and penumbra_map against the reference on a CAD-like assembly of many parts.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "test_assembly_scene.h"
#include "test_pcss_support.h"

namespace ss::test {
namespace {

TEST(ManyParts, Explore) {
    struct Variant {
        const char* name;
        AssemblyParams p;
    };
    std::vector<Variant> variants;
    for (int one = 0; one < 2; ++one)
        for (int split = 0; split < 2; ++split) {
            AssemblyParams p;
            p.oneMesh = one;
            p.splitHardEdges = split;
            p.scene = softSceneParams();
            p.scene.cameraZoom = 1.2f;
            p.scene.width = 320, p.scene.height = 240;
            const char* names[] = {"parts", "parts_split", "one", "one_split"};
            variants.push_back({names[one * 2 + split], p});
        }
    if (const char* t = std::getenv("TESS"))
        for (auto& v : variants) v.p.tessellation = std::atoi(t);
    if (const char* d = std::getenv("DIAM"))
        for (auto& v : variants) v.p.scene.lightDiameter = float(std::atof(d));
    for (auto& v : variants) {
        if (std::getenv("VAR") && std::string(v.name) != std::getenv("VAR")) continue;
        Scene scene = sceneAssembly(v.p);
        Layers ref = renderReference(scene);
        dumpPng(std::string(v.name) + "_reference", *ref.find("V"));
        const char* only = std::getenv("ONLY");
        for (std::string method : {"shadow_map", "dbuffer", "dbuffer:farthest", "penumbra_map", "pcss", "sweep"}) {
            if (only && method.find(only) == std::string::npos) continue;
            auto t0 = std::chrono::steady_clock::now();
            std::map<std::string, std::string> o;
            if (method == "dbuffer:farthest") o["umbra_rule"] = "farthest";
            Layers l = renderWith(scene, method.substr(0, method.find(':')), o);
            double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            Metrics m = compareToReference(l, ref);
            std::printf("%-12s %-17s %6.2fs %s\n", v.name, method.c_str(), s, m.toString().c_str());
            dumpPng(std::string(v.name) + "_" + method.substr(0, method.find(":")) + (o.empty() ? "" : "_far"), *l.find("V"));
        }
    }
}

}  // namespace
}  // namespace ss::test

namespace ss::test {
namespace {
TEST(ManyParts, Debug) {
    AssemblyParams p;
    p.scene = softSceneParams();
    p.scene.cameraZoom = 1.2f;
    p.scene.width = 320, p.scene.height = 240;
    p.splitHardEdges = std::getenv("SPLIT") != nullptr;
    Scene scene = sceneAssembly(p);
    Layers ref = renderReference(scene);
    RenderSettings s;
    s.extraLayers = true;
    s.options = {{"raw_layers", "true"}};
    Layers db = sharedRenderer().render(scene, 0, "dbuffer", s, nullptr);
    Metrics m = compareToReference(db, ref);
    std::printf("dbuffer %s\n", m.toString().c_str());
    dumpPng("dbg_ref", *ref.find("V"));
    dumpPng("dbg_db", *db.find("V"));
    const Image& V = *db.find("V");
    const Image& R = *ref.find("V");
    const Image& mask = *ref.find("mask");
    int shown = 0;
    for (size_t i = 0; i < V.pixels.size(); i += 37) {
        if (mask.pixels[i] < 0.5f || R.pixels[i] > 0.7f || R.pixels[i] < 0.3f || V.pixels[i] < 0.95f) continue;
        if (shown++ > 25) break;
        std::printf("px %zu,%zu ref %.2f V %.2f o %.3f uv %.3f pv %.3f s %.3f umbra_vol %.0f pen_vol %.0f rawt %.3f\n",
                    i % V.width, i / V.width, R.pixels[i], V.pixels[i], db.find("dist_occluder")->pixels[i],
                    db.find("dist_umbra")->pixels[i], db.find("dist_penumbra")->pixels[i],
                    db.find("dist_silhouette")->pixels[i], db.find("umbra_volume")->pixels[i],
                    db.find("penumbra_volume")->pixels[i], db.find("raw_t")->pixels[i]);
    }
}
}  // namespace
}  // namespace ss::test
