// How long penumbra_map's stages take at 512² and 1024² on spheres of 5k to 1M triangles, and
// penumbra_map and dbuffer on a CAD-like assembly of many finely tessellated parts.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_scenes.h"
#include "core/scene.h"
#include "geometry/silhouette.h"
#include "methods/penumbra_map.h"
#include "core/stopwatch.h"
#include "scene_cache/scene_cache.h"
#include "softshadow/softshadow.h"

namespace ss {
namespace {


Scene benchScene(int m, int resolution) {
    return bench::sphereOverGround(m, SS_MESH_CAST, LightType::Disk, resolution);
}

// args: resolution (camera and maps), m (4 m² sphere triangles)
void BM_PenumbraMapStages(benchmark::State& state) {
    const int res = int(state.range(0));
    const int m = int(state.range(1));
    Scene scene = benchScene(m, res);
    RenderSettings settings;
    settings.options = {{"shadow_map_size", std::to_string(res)}, {"debug.finish_stages", "1"}};

    // CPU stage alone: silhouette from the light centre plus cones and sheets.
    ShadowMap fitted = fitShadowMap(scene.lights()[0], scene.bounds(), res);
    auto t0 = Clock::now();
    ConesSheets g = buildPenumbraGeometry(scene, 0, fitted, scene.lights()[0].equivalentRadius(), {});
    double geometryMs = msSince(t0);

    // Shared passes (camera G-buffer + shadow map), drawn once for every method of the frame.
    // shadow_map takes no debug.finish_stages: only the map size is shared.
    RenderSettings shared;
    shared.options = {{"shadow_map_size", std::to_string(res)}};
    t0 = Clock::now();
    bench::sharedRenderer().render(scene, 0, "shadow_map", shared, nullptr);
    double sharedMs = msSince(t0);

    std::map<std::string, double> stageMs;
    double firstMs = 0.0;
    bool first = true;
    bench::StageClock clock;
    for (auto _ : state) {
        auto start = Clock::now();
        bench::sharedRenderer().render(scene, 0, "penumbra_map", clock.watch(settings), nullptr);
        auto end = Clock::now();
        double total = std::chrono::duration<double, std::milli>(end - start).count();
        state.SetIterationTime(total / 1000.0);
        if (first) {
            firstMs = total;  // includes prepare: geometry build and upload
            first = false;
            continue;
        }
        stageMs["pass2_ms"] += clock.ms("penumbra_map pass 2", "penumbra_map pass 3");
        stageMs["pass3_ms"] += clock.ms("penumbra_map pass 3", "penumbra_map readback");
        stageMs["readback_ms"] +=
            std::chrono::duration<double, std::milli>(end - clock.marks.at("penumbra_map readback")).count();
    }
    double n = std::max<double>(1.0, double(state.iterations()) - 1.0);
    state.counters["triangles"] = double(4 * m * m);
    state.counters["cones"] = double(g.cones());
    state.counters["sheets"] = double(g.sheets());
    state.counters["geometry_ms"] = geometryMs;
    state.counters["shared_passes_ms"] = sharedMs;
    state.counters["first_render_ms"] = firstMs;
    for (auto& [k, v] : stageMs) state.counters[k] = v / n;
}

// m = 35, 71, 158, 274, 500: 4.9k, 20k, 100k, 300k, 1M triangles.
BENCHMARK(BM_PenumbraMapStages)
    ->ArgsProduct({{512, 1024}, {35, 71, 158, 274, 500}})
    ->UseManualTime()
    ->Iterations(4)
    ->Unit(benchmark::kMillisecond);

// The whole render of a method on a warm frame (shared passes already drawn), to set
// penumbra_map's stage times beside the hard shadow map and pcss measured in the same run.
// args: method (0 shadow_map, 1 pcss, 2 penumbra_map), resolution, m
void BM_PenumbraMapPeers(benchmark::State& state) {
    static const char* names[] = {"shadow_map", "pcss", "penumbra_map"};
    const char* method = names[state.range(0)];
    const int res = int(state.range(1));
    Scene scene = benchScene(int(state.range(2)), res);
    RenderSettings settings;
    settings.options = {{"shadow_map_size", std::to_string(res)}};
    bench::sharedRenderer().render(scene, 0, method, settings, nullptr);  // warm: shared passes, programs
    for (auto _ : state) {
        auto start = Clock::now();
        bench::sharedRenderer().render(scene, 0, method, settings, nullptr);
        state.SetIterationTime(msSince(start) / 1000.0);
    }
    state.SetLabel(method);
}

BENCHMARK(BM_PenumbraMapPeers)
    ->ArgsProduct({{0, 1, 2}, {512, 1024}, {158}})
    ->UseManualTime()
    ->Iterations(4)
    ->Unit(benchmark::kMillisecond);

// A CAD-like assembly of 54 parts (bench::assembly) at 1024²: the whole render on a warm frame
// after the light moved (so the cones and sheets, or the volumes, are built and drawn again) and
// pass 2's share of it. Finely tessellated parts have long silhouettes of short edges: whole
// cones per silhouette vertex made pass 2 cost vertices x penumbra width².
// args: method (0 penumbra_map, 1 dbuffer, 2 shadow_map), tessellation
void BM_AssemblyRender(benchmark::State& state) {
    static const char* names[] = {"penumbra_map", "dbuffer", "shadow_map"};
    const char* method = names[state.range(0)];
    const int res = 1024;
    Scene scene = bench::assembly(int(state.range(1)), res);
    RenderSettings settings;
    settings.options = {{"shadow_map_size", std::to_string(res)}, {"debug.finish_stages", "1"}};
    if (std::string(method) == "shadow_map") settings.options.erase("debug.finish_stages");
    bench::sharedRenderer().render(scene, 0, method, settings, nullptr);  // warm: shared passes, programs
    bench::StageClock clock;
    double pass2 = 0.0;
    float nudge = 0.0f;
    for (auto _ : state) {
        Light l = scene.lights()[0];
        nudge = nudge == 0.0f ? 0.01f : 0.0f;
        l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(1.2f + nudge, 0.8f, 4.0f));
        scene.updateLight(0, l);
        auto start = Clock::now();
        bench::sharedRenderer().render(scene, 0, method, clock.watch(settings), nullptr);
        state.SetIterationTime(msSince(start) / 1000.0);
        if (std::string(method) == "penumbra_map") pass2 += clock.ms("penumbra_map pass 2", "penumbra_map pass 3");
        if (std::string(method) == "dbuffer") pass2 += clock.ms("D-buffer pass", "camera pass");
    }
    size_t triangles = 0;
    for (const Mesh& m : scene.meshes()) triangles += m.triangles.size();
    state.counters["triangles"] = double(triangles);
    state.counters["parts"] = double(scene.meshes().size() - 1);
    state.counters["light_pass_ms"] = pass2 / std::max<double>(1.0, double(state.iterations()));
    state.SetLabel(method);
}

BENCHMARK(BM_AssemblyRender)
    ->ArgsProduct({{0, 1, 2}, {1, 4, 16}})
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ss
