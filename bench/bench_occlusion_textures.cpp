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
#include "bench_meshes.h"

namespace ss {
namespace {

using Clock = std::chrono::steady_clock;

Scene benchScene(int resolution) {
    Scene s;
    s.addMesh(bench::groundSquare(6.0f));
    s.addMesh(bench::uvSphere(158, 0.8f, {0, 0, 1.3f}, SS_MESH_CAST | SS_MESH_RECEIVE));  // 100k
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
    ->ArgsProduct({{512, 1024}, {4, 8, 16}, {256, 512}, {0, 1, 2}})
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ss
