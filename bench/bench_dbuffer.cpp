// How long dbuffer's stages take at 512² and 1024² on spheres of 1k to 1M triangles.
// SPDX-License-Identifier: GPL-3.0-or-later
// Silhouettes and extrusion are CPU work done once per (scene, light) and then cached (the
// paper's frame coherence): they are timed on their first build. The D-buffer pass, the camera
// pass and the read-back are timed on every frame, after the shared camera pass and shadow map
// (BM_Foundation times those).
#include <benchmark/benchmark.h>

#include <string>

#include "bench_scenes.h"
#include "methods/dbuffer/geometry.h"
#include "softshadow/softshadow.h"

namespace ss {
namespace {

// args: camera resolution, m (4 m² sphere triangles)
void BM_DbufferStages(benchmark::State& state) {
    const int res = int(state.range(0)), m = int(state.range(1));
    Scene scene = bench::sphereOverGround(m, SS_MESH_CAST | SS_MESH_RECEIVE, LightType::Disk, res);
    // First build of the volumes (the scene is new, so the cache misses).
    std::shared_ptr<const DbufferGeometry> geo = dbufferGeometry(scene, 0, scene.bounds());
    RenderSettings settings;
    settings.extraLayers = false;
    settings.options = {{"debug.finish_stages", "1"}};
    // Shared passes and programs drawn once (a frame's other methods would share them).
    bench::sharedRenderer().render(scene, 0, "dbuffer", settings, nullptr);
    // debug.finish_stages: glFinish before each mark, so each span is that stage's GPU work. The light
    // is edited before each render: the method keeps its D-buffer while the light and the
    // geometry stay as they were, and dbuffer_pass_ms is to time the pass.
    bench::timeStages(state, scene, "dbuffer", settings,
                      {{"dbuffer_pass_ms", "D-buffer pass", "camera pass"}, {"camera_pass_readback_ms", "camera pass", "done"}},
                      [&] { scene.updateLight(0, scene.lights()[0]); });
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
