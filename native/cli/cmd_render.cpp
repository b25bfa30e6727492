// What `softshadow render` does: load a scene, render every (light, method) through the C API,
// write one multilayer EXR (and PNG previews), and summarise what was written.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>
#include <sstream>

#include "cli_common.h"
#include "progress_bar.h"

namespace ss::cli {

namespace {

// "warning: <line>" on stderr for each line of a result's warnings not printed before.
void printWarnings(const char* text, std::set<std::string>& printed) {
    std::istringstream lines(text ? text : "");
    for (std::string line; std::getline(lines, line);)
        if (!line.empty() && printed.insert(line).second) std::fprintf(stderr, "warning: %s\n", line.c_str());
}

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
    // (the library's camera check names the real limits)
    int w = args.integer("--width", 0, 1, 1 << 20), h = args.integer("--height", 0, 1, 1 << 20);
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

// Creates the preview folder before the render, so a bad one fails before anything is written.
void preparePreviewFolder(const std::string& dir) {
    std::error_code ec;
    fs::file_status st = fs::status(dir, ec);
    if (fs::exists(st) && !fs::is_directory(st))
        throw CliError("cannot write previews to '" + dir + "': it exists and is not a folder");
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw CliError("cannot write previews to '" + dir + "': " +
                       (ec ? ec.message() : std::string("not a folder")));
    if (access(dir.c_str(), W_OK) != 0)
        throw CliError("cannot write previews to '" + dir + "': the folder is not writable");
}

}  // namespace

int runRender(const std::vector<std::string>& argv) {
    Args args(argv,
              {"-m", "--method", "-l", "--light", "--width", "--height", "--samples", "--seed", "--set",
               "--backend", "--png-dir", "-o", "--output"},
              {"--no-extra", "--refine"});
    if (args.positional().size() != 1) throw CliError("render needs exactly one SCENE file");
    if (args.has("-o") && args.has("--output")) throw CliError("give -o or --output, not both");
    std::string out = args.value("-o", args.value("--output"));
    if (out.empty()) throw CliError("render needs an output file: -o OUT.exr");
    std::vector<std::string> methods;
    for (const char* opt : {"-m", "--method"})
        for (const std::string& v : args.values(opt))
            for (const std::string& m : splitList(v)) methods.push_back(m);
    if (methods.empty()) throw CliError("render needs a method: -m reference|shadow_map|...|auto");

    // Fails before a long render when the output obviously cannot be written.
    check(ss_check_output_path(out.c_str()));
    if (args.has("--png-dir")) preparePreviewFolder(args.value("--png-dir"));

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
    options.refine = args.flag("--refine") ? SS_REFINE_ON : SS_REFINE_OFF;
    std::string settings;
    for (const std::string& kv : args.values("--set")) {
        if (kv.find('=') == std::string::npos) throw CliError("--set needs key=value, got '" + kv + "'");
        settings += (settings.empty() ? "" : ";") + kv;
    }
    options.settings = settings.empty() ? nullptr : settings.c_str();

    ss_context* rawContext = nullptr;
    check(ss_context_create(parseBackend(args.value("--backend", "auto")), &rawContext));
    ContextPtr context(rawContext, ss_context_destroy);

    {
        // Every method gives at least V and mask: refuse now what the EXR could not hold.
        ss_camera_desc cam;
        check(ss_scene_get_camera(scene.get(), &cam));
        check(ss_check_exr_shape(out.c_str(), int64_t(2 * lights.size() * methods.size()), cam.width));
    }
    // Each result goes to the writer's spool (and its previews to staged files, renamed into
    // place after the EXR) as soon as it is rendered and is then released, so memory does not
    // grow with the number of lights.
    ss_exr_writer* rawWriter = nullptr;
    check(ss_exr_writer_create(out.c_str(), ss_scene_view_layer(scene.get()), &rawWriter));
    std::unique_ptr<ss_exr_writer, void (*)(ss_exr_writer*)> writer(rawWriter, ss_exr_writer_destroy);
    const bool previews = args.has("--png-dir");
    if (previews) check(ss_exr_writer_set_preview_folder(writer.get(), args.value("--png-dir").c_str()));

    struct Row {
        std::string light, asked, used, passes;
        double seconds = 0.0;
        double estimate = 0.0;  // expected RMSE against the reference; NaN: none made
    };
    std::vector<Row> rows;
    std::set<std::string> warned;  // each warning once, however many renders give it
    int32_t width = 0, height = 0;
    int passCount = 0;
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
            ResultPtr result(raw, ss_result_destroy);
            Row row;
            row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            row.light = ss_scene_light_name(scene.get(), light);
            row.asked = method;
            row.used = ss_result_method(raw);
            row.estimate = ss_result_estimated_rmse(raw);
            printWarnings(ss_result_warnings(raw), warned);
            check(ss_exr_writer_add(writer.get(), raw));
            for (int32_t i = 0; i < ss_result_layer_count(raw); ++i) {
                const char* name;
                check(ss_result_layer(raw, i, &name, nullptr, &width, &height));
                // Named by the method asked for, as the EXR names it (`auto` stays `auto`).
                std::string pass = passName(ss_result_light(raw), method.c_str(), name);
                row.passes += (row.passes.empty() ? "" : " ") + pass;
                ++passCount;
            }
            rows.push_back(std::move(row));
        }

    check(ss_exr_writer_finish(writer.get()));

    double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - total0).count();
    std::error_code ec;
    auto bytes = fs::file_size(out, ec);
    std::printf("wrote %s: %dx%d, %d passes, %.1f MB, view layer '%s'\n", out.c_str(), width, height, passCount,
                ec ? 0.0 : double(bytes) / 1e6, ss_scene_view_layer(scene.get()));
    std::printf("  %-24s %-14s %-14s %9s %9s  %s\n", "light", "asked", "method used", "seconds", "est.rmse",
                "passes");
    for (const Row& r : rows) {
        char estimate[32] = "        -";
        if (std::isfinite(r.estimate)) std::snprintf(estimate, sizeof estimate, "%9.4f", r.estimate);
        std::printf("  %-24s %-14s %-14s %9.3f %s  %s\n", r.light.c_str(), r.asked.c_str(), r.used.c_str(), r.seconds,
                    estimate, r.passes.c_str());
    }
    if (previews && passCount > 0)
        std::printf("  %d PNG previews in %s\n", passCount, args.value("--png-dir").c_str());
    std::printf("  total %.3f s\n", total);
    return 0;
}

}  // namespace ss::cli
