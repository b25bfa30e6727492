// How long occlusion_textures' stages (slicing, pre-filter per type, shading) take.
// SPDX-License-Identifier: GPL-3.0-or-later
// At 512² and 1024² with 4, 8, 16 slices of 256² and 512², on a 100k-triangle sphere over a
// ground plane.
#include <benchmark/benchmark.h>

#include <string>

#include "bench_scenes.h"
#include "softshadow/softshadow.h"

namespace ss {
namespace {

// args: camera resolution, slices, slice resolution, filter (0 mipmap, 1 nbuffer, 2 sat)
void BM_OcclusionTexturesStages(benchmark::State& state) {
    static const char* filters[] = {"mipmap", "nbuffer", "sat"};
    const int res = int(state.range(0));
    Scene scene = bench::sphereOverGround(158, SS_MESH_CAST | SS_MESH_RECEIVE, LightType::Rectangle, res);  // 100k
    RenderSettings settings;
    settings.extraLayers = false;
    settings.options = {{"slices", std::to_string(state.range(1))},
                        {"resolution", std::to_string(state.range(2))},
                        {"filter", filters[state.range(3)]},
                        {"debug.finish_stages", "1"}};
    bench::sharedRenderer().render(scene, 0, "occlusion_textures", settings, nullptr);  // warm: passes, programs
    // The light edited before each render: the method keeps its slices while the light and the
    // geometry stay as they were, and slicing_ms is to time the slicing pass.
    bench::timeStages(state, scene, "occlusion_textures", settings,
                      {{"slicing_ms", "slicing", "pre-filtering"},
                       {"prefilter_ms", "pre-filtering", "shading"},
                       {"shading_ms", "shading", "done"}},  // shading includes the read-back
                      [&] { scene.updateLight(0, scene.lights()[0]); });
    state.SetLabel(filters[state.range(3)]);
}

BENCHMARK(BM_OcclusionTexturesStages)
    ->ArgsProduct({{512, 1024}, {4, 8, 16}, {256, 512}, {0, 1, 2}})
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ss
