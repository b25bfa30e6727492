// How long sweep's geometry stages take for 3, 16 and 64 light samples on 5k to 500k triangles.
// SPDX-License-Identifier: GPL-3.0-or-later
// One core, CPU only: silhouettes (potential silhouette edges projected per sample), the
// per-sample sweeps (hard outlines), the merge into rings, the fill (triangulation), and the
// irradiance weights; the camera pass that draws the shadow mesh is timed by BM_Foundation.
// The paper's case is ~5,000 vertices (10k triangles) with 3 samples at 10 fps on a 1 GHz CPU.
#include <benchmark/benchmark.h>

#include "bench_scenes.h"
#include "methods/sweep/shadow.h"
#include "softshadow/softshadow.h"

namespace ss {
namespace {

// args: samples, m (4 m² sphere triangles), irradiance weights (0 equal, 1 irradiance)
void BM_SweepStages(benchmark::State& state) {
    Scene scene = bench::sphereOverGround(int(state.range(1)), SS_MESH_CAST | SS_MESH_RECEIVE, LightType::Disk, 512);
    SweepOptions options;
    options.samples = int(state.range(0));
    options.irradianceWeights = state.range(2) != 0;
    SweepTimings sum;
    size_t triangles = 0;
    for (auto _ : state) {
        SweepShadow shadow = computeSweepShadow(scene, 0, options);
        const SweepTimings& t = shadow.timings;
        state.SetIterationTime((t.silhouettesMs + t.sweepMs + t.mergeMs + t.fillMs + t.weightsMs) / 1000.0);
        sum.silhouettesMs += t.silhouettesMs, sum.sweepMs += t.sweepMs, sum.mergeMs += t.mergeMs;
        sum.fillMs += t.fillMs, sum.weightsMs += t.weightsMs;
        triangles = shadow.mesh.indices.size() / 3;
    }
    const double n = double(state.iterations());
    state.counters["triangles"] = double(4 * state.range(1) * state.range(1));
    state.counters["vertices"] = double(scene.meshes()[1].positions.size());
    state.counters["silhouettes_ms"] = sum.silhouettesMs / n;
    state.counters["sweep_ms"] = sum.sweepMs / n;
    state.counters["merge_ms"] = sum.mergeMs / n;
    state.counters["fill_ms"] = sum.fillMs / n;
    state.counters["weights_ms"] = sum.weightsMs / n;
    state.counters["shadow_triangles"] = double(triangles);
    state.SetLabel(options.irradianceWeights ? "irradiance weights" : "equal weights");
}

// m = 35, 50, 112, 354: 4.9k, 10k (the paper's and the target's 5k vertices), 50k, 500k triangles.
BENCHMARK(BM_SweepStages)
    ->ArgsProduct({{3, 16, 64}, {35, 50, 112, 354}, {0, 1}})
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ss
