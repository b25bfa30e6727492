// How many milliseconds each stage of every method takes (shared passes, prepare, render, readback)
// at 512² and 1024² on the example scene and on a ~100k-triangle torus.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_scenes.h"
#include "core/error.h"
#include "core/scene.h"
#include "io/scene_file.h"
#include "renderer/renderer.h"
#include "softshadow/softshadow.h"
#include "stage_timing.h"

namespace ss {
namespace {

using bench::runOnce;
using bench::Stages;

// A torus of 2 nu nv triangles (nu = 316, nv = 158: 99,856) lying on z = c.z, outward winding.
Mesh torus(int nu, int nv, float major, float minor, glm::vec3 c) {
    Mesh m;
    m.name = "torus";
    m.flags = SS_MESH_CAST | SS_MESH_RECEIVE;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            float u = 2.0f * float(M_PI) * float(i) / float(nu), v = 2.0f * float(M_PI) * float(j) / float(nv);
            float r = major + minor * std::cos(v);
            m.objectPositions.push_back(c + glm::vec3(r * std::cos(u), r * std::sin(u), minor * std::sin(v)));
        }
    auto at = [&](int i, int j) { return uint32_t((i % nu) * nv + (j % nv)); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

Scene torusScene(int resolution) {
    Scene s;
    s.addMesh(bench::groundSquare(6.0f));
    s.addMesh(torus(316, 158, 1.0f, 0.35f, {0, 0, 1.2f}));
    Light l;
    l.name = "Disk";
    l.type = LightType::Disk;
    l.lightToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0.8f, 0.5f, 4.0f));
    l.size = l.sizeY = 1.5f;
    s.addLight(l);
    s.setCamera(makeLookAtCamera({0, -4.5f, 6.5f}, {0, 0, 0.5f}, {0, 0, 1}, glm::radians(40.0f), resolution,
                                 resolution, 0.1f, 50.0f));
    return s;
}

// The example, resampled to resolution² (the projection is kept: only the pixel count changes).
Scene demoScene(int resolution) {
    Scene s = loadSceneFile(std::string(SS_SOURCE_DIR) + "/examples/scenes/demo.json");
    Camera c = s.camera();
    c.width = c.height = resolution;
    s.setCamera(c);
    return s;
}

// args: scene (0 example, 1 torus 100k), resolution, method index in methodNames()
void BM_Foundation(benchmark::State& state) {
    const int res = int(state.range(1));
    const std::string method = methodNames().at(size_t(state.range(2)));
    Scene scene = state.range(0) == 0 ? demoScene(res) : torusScene(res);
    size_t triangles = 0;
    for (const Mesh& m : scene.meshes()) triangles += m.triangles.size();
    try {
        if (method != "reference") runOnce(scene, method);  // warm-up: programs compiled, caches hot
    } catch (const std::exception& e) {
        state.SkipWithError((method + ": " + e.what()).c_str());
        for (auto _ : state) {
        }
        return;
    }
    Stages sum;
    for (auto _ : state) {
        Stages s;
        try {
            s = runOnce(scene, method);
        } catch (const std::exception& e) {
            state.SkipWithError((method + ": " + e.what()).c_str());
            break;
        }
        double total = s.meshUpload + s.cameraPass + s.shadowMap + s.prepare + s.render;
        state.SetIterationTime(total / 1000.0);
        sum.meshUpload += s.meshUpload, sum.cameraPass += s.cameraPass, sum.shadowMap += s.shadowMap;
        sum.prepare += s.prepare, sum.render += s.render, sum.readback += s.readback;
    }
    double n = std::max<double>(1.0, double(state.iterations()));
    state.counters["triangles"] = double(triangles);
    state.counters["mesh_upload_ms"] = sum.meshUpload / n;
    state.counters["camera_pass_ms"] = sum.cameraPass / n;
    state.counters["shadow_map_ms"] = sum.shadowMap / n;
    state.counters["prepare_ms"] = sum.prepare / n;
    state.counters["render_ms"] = sum.render / n;
    state.counters["readback_ms"] = sum.readback / n;
    state.SetLabel(std::string(state.range(0) == 0 ? "example" : "torus100k") + " " + method);
}

// GL methods get a warm-up and two timed cold frames; the CPU reference (seconds per frame) one.
void foundationArgs(benchmark::internal::Benchmark* b, bool reference) {
    b->ArgNames({"scene", "res", "method"});
    for (int scene : {0, 1})
        for (int res : {512, 1024})
            for (size_t m = 0; m < methodNames().size(); ++m)
                // The CPU reference at 512² only: at 1024² it costs minutes and says nothing new
                // (its time scales with the pixel count).
                if ((methodNames()[m] == "reference") == reference && !(reference && res > 512))
                    b->Args({scene, res, int64_t(m)});
}

BENCHMARK(BM_Foundation)
    ->Apply([](benchmark::internal::Benchmark* b) { foundationArgs(b, false); })
    ->UseManualTime()
    ->Iterations(2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Foundation)
    ->Apply([](benchmark::internal::Benchmark* b) { foundationArgs(b, true); })
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ss
