// Checks dbuffer against the ray-traced reference on the shared scenes, and against shadow_map.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "io/metrics.h"
#include "io/png_preview.h"
#include "methods/method.h"
#include "pipeline/renderer.h"
#include "softshadow/softshadow.h"
#include "test_scenes.h"

namespace ss {
namespace {

Layers run(Renderer& renderer, const Scene& scene, const std::string& method, int samples = 0) {
    RenderSettings s;
    s.samples = samples;
    std::string used;
    return renderer.render(scene, 0, method, s, &used);
}

const Image& layer(const Layers& l, const char* name) {
    const Image* img = l.find(name);
    if (!img) throw std::runtime_error(std::string("missing layer ") + name);
    return *img;
}

TEST(DbufferQuality, SharedScenesPrint) {
    Renderer renderer(SS_BACKEND_AUTO);
    int samples = test::quickTests() ? 64 : 256;
    test::SceneParams params;
    if (getenv("SS_DBUFFER_DUMP")) params.width = 480, params.height = 360;
    for (auto& [name, scene] : test::sharedScenes(params)) {
        Layers ref = run(renderer, scene, "reference", samples);
        Layers db = run(renderer, scene, "dbuffer");
        const Image* mask = ref.find("mask");
        Metrics mdb = compareVisibility(layer(db, "V"), layer(ref, "V"), mask);
        std::printf("%s dbuffer: %s\n", name.c_str(), mdb.toString().c_str());
        if (getenv("SS_DBUFFER_DUMP")) {
            writePngPreview("/tmp/dbq/" + name + "_ref.png", layer(ref, "V"));
            for (auto& [ln, img] : db.items) {
                Image v = img;
                if (ln.rfind("dist_", 0) == 0) for (float& x : v.pixels) x /= 10.0f;
                writePngPreview("/tmp/dbq/" + name + "_db_" + ln + ".png", v);
            }
        }
        try {
            Layers sm = run(renderer, scene, "shadow_map");
            Metrics msm = compareVisibility(layer(sm, "V"), layer(ref, "V"), mask);
            std::printf("%s shadow_map: %s\n", name.c_str(), msm.toString().c_str());
        } catch (const std::exception& e) {
            std::printf("shadow_map: %s\n", e.what());
        }
    }
}

}  // namespace
}  // namespace ss

namespace ss {
namespace {
TEST(DbufferDebug, DISABLED_Column) {
    Renderer renderer(SS_BACKEND_AUTO);
    test::SceneParams params;
    params.width = 480, params.height = 360;
    int which = getenv("SS_DBG_SCENE") ? atoi(getenv("SS_DBG_SCENE")) : 2;
    int x = getenv("SS_DBG_X") ? atoi(getenv("SS_DBG_X")) : 220;
    auto scenes = test::sharedScenes(params);
    Scene& scene = scenes[which].scene;
    Layers ref = run(renderer, scene, "reference", 128);
    Layers db = run(renderer, scene, "dbuffer");
    bool row = getenv("SS_DBG_ROW") != nullptr;
    for (int i = 0; i < 60; ++i) {
        int y = row ? atoi(getenv("SS_DBG_ROW")) : 150 + 2 * i;
        int xx = row ? 100 + 4 * i : x;
        #define x xx
        std::printf("x=%d y=%d ref=%.3f V=%.3f mask=%.0f u=%.0f p=%.0f o=%.4f uv=%.4f pv=%.4f s=%.4f\n", xx, y,
                    layer(ref, "V").at(x, y), layer(db, "V").at(x, y), layer(db, "mask").at(x, y),
                    layer(db, "umbra").at(x, y), layer(db, "penumbra").at(x, y),
                    layer(db, "dist_occluder").at(x, y), layer(db, "dist_umbra").at(x, y),
                    layer(db, "dist_penumbra").at(x, y), layer(db, "dist_silhouette").at(x, y));
        #undef x
    }
}
}  // namespace
}  // namespace ss
