// How long occlusion_textures' stages (slicing, pre-filter per type, shading) take.
// SPDX-License-Identifier: GPL-3.0-or-later
// At 512² and 1024² with 4, 8, 16 slices of 256² and 512², on a 100k-triangle sphere over a
// ground plane.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/scene.h"
#include "pipeline/renderer.h"
#include "softshadow/softshadow.h"

namespace ss {
namespace {

using Clock = std::chrono::steady_clock;

// A latitude-longitude sphere of 2 n (n - 1) quads as triangles (n = 224: ~100k triangles).
Mesh sphere(int n, float r, glm::vec3 c) {
    Mesh m;
    m.name = "sphere";
    m.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i < 2 * n; ++i) {
            float th = float(M_PI) * float(j) / float(n), ph = float(M_PI) * float(i) / float(n);
            m.positions.push_back(c + r * glm::vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
        }
    auto at = [&](int j, int i) { return uint32_t(j * 2 * n + (i % (2 * n))); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < 2 * n; ++i) {
            m.triangles.push_back({at(j, i), at(j + 1, i), at(j + 1, i + 1)});
            m.triangles.push_back({at(j, i), at(j + 1, i + 1), at(j, i + 1)});
        }
    m.finalize();
    return m;
}

Scene benchScene(int resolution) {
    Scene s;
    Mesh ground;
    ground.name = "ground";
    ground.positions = {{-6, -6, 0}, {6, -6, 0}, {6, 6, 0}, {-6, 6, 0}};
    ground.triangles = {{0, 1, 2}, {0, 2, 3}};
    ground.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    ground.finalize();
    s.addMesh(ground);
    s.addMesh(sphere(224, 0.8f, {0, 0, 1.3f}));
    Light l;
    l.name = "Area";
    l.type = LightType::Rectangle;
    l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.8f, 4.0f));
    l.size = 1.5f;
    l.sizeY = 1.0f;
    s.addLight(l);
    s.setCamera(makeLookAtCamera({0, -2.5f, 8}, {0, 0, 0}, {0, 1, 0}, glm::radians(40.0f), resolution, resolution,
                                 0.1f, 50.0f));
    return s;
}

Renderer& renderer() {
    static Renderer* r = new Renderer(SS_BACKEND_AUTO);  // joined by shutdownRenderThreads()
    return *r;
}

// args: camera resolution, slices, slice resolution, filter (0 mipmap, 1 nbuffer, 2 sat)
void BM_OcclusionTexturesStages(benchmark::State& state) {
    static const char* filters[] = {"mipmap", "nbuffer", "sat"};
    const int res = int(state.range(0));
    Scene scene = benchScene(res);
    RenderSettings settings;
    settings.extraLayers = false;
    settings.options = {{"slices", std::to_string(state.range(1))},
                        {"resolution", std::to_string(state.range(2))},
                        {"filter", filters[state.range(3)]},
                        {"finish_stages", "1"}};
    renderer().render(scene, 0, "occlusion_textures", settings, nullptr);  // warm: shared passes, programs
    std::map<std::string, double> ms;
    for (auto _ : state) {
        std::map<std::string, Clock::time_point> marks;
        RenderSettings s = settings;
        s.progress = [&](float, const char* stage) {
            marks[stage] = Clock::now();
            return true;
        };
        auto start = Clock::now();
        renderer().render(scene, 0, "occlusion_textures", s, nullptr);
        auto end = Clock::now();
        state.SetIterationTime(std::chrono::duration<double>(end - start).count());
        auto span = [&](Clock::time_point a, Clock::time_point b) {
            return std::chrono::duration<double, std::milli>(b - a).count();
        };
        ms["slicing_ms"] += span(marks["slicing"], marks["pre-filtering"]);
        ms["prefilter_ms"] += span(marks["pre-filtering"], marks["shading"]);
        ms["shading_ms"] += span(marks["shading"], marks["done"]);  // includes the read-back
    }
    for (auto& [k, v] : ms) state.counters[k] = v / double(state.iterations());
    state.SetLabel(filters[state.range(3)]);
}

BENCHMARK(BM_OcclusionTexturesStages)
    ->ArgsProduct({{512, 1024}, {4, 16}, {512}, {0, 1, 2}})
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ss
