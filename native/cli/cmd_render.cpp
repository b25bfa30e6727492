// What `softshadow render` does: load a scene, render every (light, method) through the C API,
// write one multilayer EXR (and PNG previews), and summarise what was written.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli_common.h"
#include "progress_bar.h"

namespace ss::cli {

namespace {

namespace fs = std::filesystem;

using ScenePtr = std::unique_ptr<ss_scene, void (*)(ss_scene*)>;
using ContextPtr = std::unique_ptr<ss_context, void (*)(ss_context*)>;
using ResultPtr = std::unique_ptr<ss_result, void (*)(ss_result*)>;

// --width/--height change the pixel count and keep the projection (the same picture, sampled
// finer or coarser); one of them alone keeps the aspect ratio.
void overrideResolution(ss_scene* scene, const Args& args) {
    if (!args.has("--width") && !args.has("--height")) return;
    ss_camera_desc cam;
    check(ss_scene_get_camera(scene, &cam));
    int w = args.integer("--width", 0, 1, 32768), h = args.integer("--height", 0, 1, 32768);
    if (w == 0) w = std::max(1, int(std::lround(double(cam.width) * h / cam.height)));
    if (h == 0) h = std::max(1, int(std::lround(double(cam.height) * w / cam.width)));
    cam.width = w;
    cam.height = h;
    check(ss_scene_set_camera(scene, &cam));
}

// The lights named with -l (comma lists, repeatable), or every light that casts shadows.
std::vector<int32_t> chooseLights(ss_scene* scene, const std::vector<std::string>& requested) {
    std::vector<int32_t> out;
    int32_t count = ss_scene_light_count(scene);
    if (!requested.empty()) {
        for (const std::string& v : requested)
            for (const std::string& name : splitList(v)) {
                int32_t found = -1;
                for (int32_t i = 0; i < count; ++i)
                    if (name == ss_scene_light_name(scene, i)) found = i;
                if (found < 0) {
                    std::string known;
                    for (int32_t i = 0; i < count; ++i)
                        known += std::string(known.empty() ? "" : ", ") + ss_scene_light_name(scene, i);
                    throw CliError("the scene has no light named '" + name + "' (lights: " +
                                   (known.empty() ? "none" : known) + ")");
                }
                out.push_back(found);
            }
        return out;
    }
    for (int32_t i = 0; i < count; ++i) {
        ss_light_desc d;
        check(ss_scene_get_light(scene, i, &d));
        if (d.cast_shadows) out.push_back(i);
    }
    if (out.empty()) throw CliError("the scene has no light that casts shadows");
    return out;
}

// Fails before a long render when the output obviously cannot be written.
void checkWritable(const std::string& out) {
    fs::path p(out);
    fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::error_code ec;
    if (fs::is_directory(p, ec)) throw CliError("cannot write '" + out + "': it is a directory");
    if (!fs::is_directory(dir, ec))
        throw CliError("cannot write '" + out + "': folder '" + dir.string() + "' does not exist");
    if (access(dir.c_str(), W_OK) != 0)
        throw CliError("cannot write '" + out + "': folder '" + dir.string() + "' is not writable");
}

}  // namespace

int runRender(const std::vector<std::string>& argv) {
    Args args(argv, {"-m", "--method", "-l", "--light", "--width", "--height", "--samples", "--seed",
                     "--set", "--backend", "--png-dir", "-o", "--output"},
              {"--no-extra"});
    if (args.positional().size() != 1) throw CliError("render needs exactly one SCENE file");
    std::string out = args.value("-o", args.value("--output"));
    if (out.empty()) throw CliError("render needs an output file: -o OUT.exr");
    std::vector<std::string> methods;
    for (const char* opt : {"-m", "--method"})
        for (const std::string& v : args.values(opt))
            for (const std::string& m : splitList(v)) methods.push_back(m);
    if (methods.empty()) throw CliError("render needs a method: -m reference|shadow_map|...|auto");

    checkWritable(out);

    ss_scene* rawScene = nullptr;
    check(ss_scene_load(args.positional()[0].c_str(), &rawScene));
    ScenePtr scene(rawScene, ss_scene_destroy);
    overrideResolution(scene.get(), args);
    std::vector<std::string> lightNames = args.values("-l");
    for (const std::string& v : args.values("--light")) lightNames.push_back(v);
    std::vector<int32_t> lights = chooseLights(scene.get(), lightNames);

    ss_render_options options;
    ss_render_options_default(&options);
    options.samples = args.integer("--samples", 0, 0, 1 << 24);
    if (args.has("--seed")) options.seed = uint32_t(args.integer("--seed", 1, 0, 2147483647));
    options.extra_layers = args.flag("--no-extra") ? 0 : 1;
    std::string settings;
    for (const std::string& kv : args.values("--set")) {
        if (kv.find('=') == std::string::npos) throw CliError("--set needs key=value, got '" + kv + "'");
        settings += (settings.empty() ? "" : ";") + kv;
    }
    options.settings = settings.empty() ? nullptr : settings.c_str();

    ss_context* rawContext = nullptr;
    check(ss_context_create(parseBackend(args.value("--backend", "auto")), &rawContext));
    ContextPtr context(rawContext, ss_context_destroy);

    std::vector<ResultPtr> results;
    std::vector<double> seconds;
    auto total0 = std::chrono::steady_clock::now();
    for (int32_t light : lights)
        for (const std::string& method : methods) {
            std::string label = std::string(ss_scene_light_name(scene.get(), light)) + " " + method;
            ProgressBar bar(label);
            options.progress = &ProgressBar::callback;
            options.progress_user = &bar;
            ss_result* raw = nullptr;
            auto t0 = std::chrono::steady_clock::now();
            ss_status status = ss_render(context.get(), scene.get(), light, method.c_str(), &options, &raw);
            bar.finish();
            check(status);
            seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            results.emplace_back(raw, ss_result_destroy);
        }

    std::vector<const ss_result*> raws;
    for (auto& r : results) raws.push_back(r.get());
    check(ss_write_exr(out.c_str(), ss_scene_view_layer(scene.get()), raws.data(), int32_t(raws.size())));

    std::vector<std::string> pngs;
    if (args.has("--png-dir")) {
        std::string dir = args.value("--png-dir");
        try {
            std::error_code ec;
            fs::create_directories(dir, ec);
            for (auto& r : results)
                for (int32_t i = 0; i < ss_result_layer_count(r.get()); ++i) {
                    const char* name;
                    const float* pixels;
                    int32_t w, h;
                    check(ss_result_layer(r.get(), i, &name, &pixels, &w, &h));
                    std::string path = (fs::path(dir) / (passName(ss_result_light(r.get()),
                                                                  ss_result_method(r.get()), name) +
                                                         ".png")).string();
                    check(ss_write_png_preview(path.c_str(), pixels, w, h));
                    pngs.push_back(path);
                }
        } catch (const std::exception&) {
            // No output left behind: a failed preview takes the EXR and earlier previews with it.
            std::error_code ignored;
            for (const std::string& p : pngs) fs::remove(p, ignored);
            fs::remove(out, ignored);
            throw;
        }
    }

    double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - total0).count();
    int32_t w = 0, h = 0;
    int passes = 0;
    for (auto& r : results) passes += ss_result_layer_count(r.get());
    ss_result_layer(results[0].get(), 0, nullptr, nullptr, &w, &h);
    std::error_code ec;
    auto bytes = fs::file_size(out, ec);
    std::printf("wrote %s: %dx%d, %d passes, %.1f MB, view layer '%s'\n", out.c_str(), w, h, passes,
                ec ? 0.0 : double(bytes) / 1e6, ss_scene_view_layer(scene.get()));
    std::printf("  %-24s %-14s %-14s %9s  %s\n", "light", "asked", "method used", "seconds", "passes");
    size_t k = 0;
    for (int32_t light : lights)
        for (const std::string& method : methods) {
            ss_result* r = results[k].get();
            std::string passList;
            for (int32_t i = 0; i < ss_result_layer_count(r); ++i) {
                const char* name;
                ss_result_layer(r, i, &name, nullptr, nullptr, nullptr);
                passList += std::string(passList.empty() ? "" : " ") +
                            passName(ss_result_light(r), ss_result_method(r), name);
            }
            std::printf("  %-24s %-14s %-14s %9.3f  %s\n", ss_scene_light_name(scene.get(), light),
                        method.c_str(), ss_result_method(r), seconds[k], passList.c_str());
            ++k;
        }
    if (!pngs.empty()) std::printf("  %zu PNG previews in %s\n", pngs.size(), args.value("--png-dir").c_str());
    std::printf("  total %.3f s\n", total);
    return 0;
}

}  // namespace ss::cli
