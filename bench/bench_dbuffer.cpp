// How long dbuffer's stages take at 512² and 1024² on spheres of 1k to 1M triangles.
// SPDX-License-Identifier: GPL-3.0-or-later
// Silhouettes and extrusion are CPU work done once per (scene, light) and then cached (the
// paper's frame coherence): they are timed on their first build. The D-buffer pass, the camera
// pass and the read-back are timed on every frame, after the shared camera pass and shadow map
// (BM_Foundation times those).
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_meshes.h"
#include "core/scene.h"
#include "methods/dbuffer_geometry.h"
#include "pipeline/renderer.h"
#include "softshadow/softshadow.h"

namespace ss {
namespace {

using Clock = std::chrono::steady_clock;

Scene benchScene(int m, int resolution) {
    Scene s;
    s.addMesh(bench::groundSquare(6.0f));
    s.addMesh(bench::uvSphere(m, 0.8f, {0, 0, 1.3f}, SS_MESH_CAST | SS_MESH_RECEIVE));
    Light l;
    l.name = "Disk";
    l.type = LightType::Disk;
    l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.8f, 4.0f));
    l.size = l.sizeY = 1.5f;
    s.addLight(l);
    s.setCamera(makeLookAtCamera({0, -2.5f, 8}, {0, 0, 0}, {0, 1, 0}, glm::radians(40.0f), resolution,
                                 resolution, 0.1f, 50.0f));
    return s;
}

Renderer& renderer() {
    static Renderer* r = new Renderer(SS_BACKEND_AUTO);  // joined by shutdownRenderThreads()
    return *r;
}

// args: camera resolution, m (4 m² sphere triangles)
void BM_DbufferStages(benchmark::State& state) {
    const int res = int(state.range(0)), m = int(state.range(1));
    Scene scene = benchScene(m, res);
    // First build of the volumes (the scene is new, so the cache misses).
    std::shared_ptr<const DbufferGeometry> geo = dbufferGeometry(scene, 0);
    RenderSettings settings;
    settings.extraLayers = false;
    settings.options = {{"finish_stages", "1"}};
    // Shared passes and programs drawn once (a frame's other methods would share them).
    renderer().render(scene, 0, "dbuffer", settings, nullptr);
    std::map<std::string, double> ms;
    for (auto _ : state) {
        std::map<std::string, Clock::time_point> marks;
        RenderSettings s = settings;
        s.progress = [&](float, const char* stage) {
            marks[stage] = Clock::now();
            return true;
        };
        auto start = Clock::now();
        renderer().render(scene, 0, "dbuffer", s, nullptr);
        auto end = Clock::now();
        state.SetIterationTime(std::chrono::duration<double>(end - start).count());
        auto span = [&](Clock::time_point a, Clock::time_point b) {
            return std::chrono::duration<double, std::milli>(b - a).count();
        };
        // finish_stages: glFinish before each mark, so each span is that stage's GPU work.
        ms["dbuffer_pass_ms"] += span(marks["D-buffer pass"], marks["camera pass"]);
        ms["camera_pass_readback_ms"] += span(marks["camera pass"], marks["done"]);
    }
    for (auto& [k, v] : ms) state.counters[k] = v / double(state.iterations());
    state.counters["triangles"] = double(4 * m * m);
    state.counters["silhouettes_ms"] = geo->silhouetteMs;
    state.counters["extrusion_ms"] = geo->extrusionMs;
    state.counters["volume_vertices"] = double(geo->volumes.umbra.size() + geo->volumes.penumbra.size());
}

// m = 16, 50, 158, 500: 1k, 10k, 100k, 1M triangles.
BENCHMARK(BM_DbufferStages)
    ->ArgsProduct({{512, 1024}, {16, 50, 158, 500}})
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ss
