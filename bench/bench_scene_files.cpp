// How long each of our GL methods takes per frame, stage by stage, on the Blender benchmark
// scenes (scene files listed in SS_BENCH_SCENES), and what it rendered (EXR per method).
// SPDX-License-Identifier: GPL-3.0-or-later
// SS_BENCH_SCENES="name=path;name=path", SS_BENCH_OUT=folder: writes folder/<name>/<key>.exr.
// Unset: registers nothing. Registration runs before main (a static initialiser), since
// bench_main.cpp owns main.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/settings.h"
#include "io/exr_file.h"
#include "io/pass_names.h"
#include "io/scene_file.h"
#include "methods/method.h"
#include "stage_timing.h"

namespace ss {
namespace {

// A method still reporting progress after kBudgetSeconds on one frame is cancelled (reported as
// skipped), so one pathological (method, scene) pair cannot stall the whole benchmark.
constexpr double kBudgetSeconds = 120.0;
constexpr double kSlowSeconds = 10.0;

// A method at a setting: `key` names its row and EXR (method, or method-tag for a non-default
// setting; the EXR's passes keep the method's own names so `compare` pairs them).
struct Variant {
    std::string method, key, settings;
    int samples = 0;  // the render's sample count (sweep's light samples); 0: the default
};

// Every GL method at its defaults, plus the settings a user would reach for next: more slices,
// more PCF samples, more light samples; and penumbra_map as the paper wrote it. Each is one more point on the error-vs-time plots.
std::vector<Variant> variants() {
    std::vector<Variant> v;
    for (const std::string& method : methodNames())
        if (method != "reference") v.push_back({method, method, ""});  // CPU: through the CLI
    v.push_back({"occlusion_textures", "occlusion_textures-16", "slices=16"});
    v.push_back({"pcss", "pcss-64", "blocker_samples=32;pcf_samples=64"});
    v.push_back({"sweep", "sweep-64", "", 64});
    // The paper's own intensity curve, beside the default (docs/methods/penumbra_map.md).
    v.push_back({"penumbra_map", "penumbra_map-paper", "intensity=paper"});
    return v;
}

void runSceneFile(benchmark::State& state, const std::string& name, const std::string& path,
                  const Variant& variant, const std::string& outDir) {
    const std::string& method = variant.method;
    const std::map<std::string, std::string> options = parseSettings(variant.settings);
    Scene scene = loadSceneFile(path);
    size_t triangles = 0;
    for (const Mesh& m : scene.meshes()) triangles += m.triangles.size();
    Layers layers;
    bench::Stages warm;
    try {
        warm = bench::runOnce(scene, method, &layers, kBudgetSeconds, options, variant.samples);  // warm-up: programs compiled
    } catch (const std::exception& e) {
        state.SkipWithError((method + ": " + e.what()).c_str());
        for (auto _ : state) {
        }
        return;
    }
    bench::Stages sum;
    // A frame slower than kSlowSeconds is timed once (its warm-up), to bound the run.
    const bool slow = warm.total() > kSlowSeconds * 1000.0;
    for (auto _ : state) {
        bench::Stages s = slow ? warm : bench::runOnce(scene, method, nullptr, 0.0, options, variant.samples);
        state.SetIterationTime(s.total() / 1000.0);
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
    state.counters["timed_once"] = slow ? 1.0 : 0.0;
    state.SetLabel(name + " " + variant.key);

    std::filesystem::create_directories(std::filesystem::path(outDir) / name);
    const std::string light = scene.lights()[0].name;
    std::vector<ExrPassRef> passes;
    for (const char* layer : {"V", "mask"})
        if (const Image* img = layers.find(layer)) passes.push_back({passName(light, method, layer), img});
    writeMultilayerExr((std::filesystem::path(outDir) / name / (variant.key + ".exr")).string(), scene.viewLayer(),
                       passes);
}

const bool registered = [] {
    const char* list = std::getenv("SS_BENCH_SCENES");
    const char* out = std::getenv("SS_BENCH_OUT");
    if (!list || !out) return false;
    // "name=path;name=path": the same form as method settings, read by the same parser.
    for (const auto& [name, path] : parseSettings(list)) {
        for (const Variant& variant : variants()) {
            benchmark::RegisterBenchmark(("BM_SceneFile/" + name + "/" + variant.key).c_str(),
                                         [=](benchmark::State& st) { runSceneFile(st, name, path, variant, out); })
                ->UseManualTime()
                ->Iterations(2)
                ->Unit(benchmark::kMillisecond);
        }
    }
    return true;
}();

}  // namespace
}  // namespace ss
