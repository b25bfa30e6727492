// Checks that a result's error estimate reaches the user: the C API, the CLI's render report and
// the EXR header.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "cli_run.h"
#include "io/exr_file.h"
#include "softshadow/softshadow.h"

namespace {

// "<pass>=<number>;..." -> the number of `pass`, NaN when absent.
double estimateOf(const std::string& attribute, const std::string& pass) {
    size_t at = attribute.find(pass + "=");
    if (at == std::string::npos) return std::nan("");
    return std::strtod(attribute.c_str() + at + pass.size() + 1, nullptr);
}

TEST(ErrorEstimate, CApiGivesItForAutoAndOnRequestForAMethod) {
    ss_scene* scene = nullptr;
    ASSERT_EQ(ss_scene_load(SS_SOURCE_DIR "/examples/scenes/demo.json", &scene), SS_OK) << ss_last_error();
    ss_camera_desc cam;
    ASSERT_EQ(ss_scene_get_camera(scene, &cam), SS_OK);
    cam.width = 96, cam.height = 72;
    ASSERT_EQ(ss_scene_set_camera(scene, &cam), SS_OK);
    ss_context* context = nullptr;
    ASSERT_EQ(ss_context_create(SS_BACKEND_AUTO, &context), SS_OK);
    ss_render_options options;
    ss_render_options_default(&options);
    auto estimate = [&](const char* method, const char* settings) {
        options.settings = settings;
        ss_result* result = nullptr;
        EXPECT_EQ(ss_render(context, scene, 0, method, &options, &result), SS_OK) << ss_last_error();
        double e = ss_result_estimated_rmse(result);
        ss_result_destroy(result);
        return e;
    };
    const double autoEstimate = estimate("auto", nullptr);
    EXPECT_TRUE(std::isfinite(autoEstimate) && autoEstimate >= 0.0 && autoEstimate < 0.2) << autoEstimate;
    EXPECT_TRUE(std::isnan(estimate("pcss", nullptr)));
    const double pcss = estimate("pcss", "estimate_rmse=1");
    EXPECT_TRUE(std::isfinite(pcss) && pcss >= autoEstimate) << pcss << " vs auto " << autoEstimate;
    EXPECT_TRUE(std::isnan(ss_result_estimated_rmse(nullptr)));
    // auto renders at most three candidates at full size here (pcss, dbuffer, sweep under the
    // demo's disk light; shadow_map, penumbra_map and occlusion_textures are left out).
    auto rendered = [&](const char* method) {
        options.settings = nullptr;
        ss_result* result = nullptr;
        EXPECT_EQ(ss_render(context, scene, 0, method, &options, &result), SS_OK) << ss_last_error();
        const int32_t n = ss_result_methods_rendered(result);
        ss_result_destroy(result);
        return n;
    };
    const int32_t autoRendered = rendered("auto");
    EXPECT_GE(autoRendered, 1);
    EXPECT_LE(autoRendered, 3);
    EXPECT_EQ(rendered("pcss"), 1);
    EXPECT_EQ(ss_result_methods_rendered(nullptr), 0);
    ss_context_destroy(context);
    ss_scene_destroy(scene);
}

TEST(ErrorEstimate, CliPrintsItAndTheExrHeaderKeepsIt) {
    fs::path dir = tempDir("estimate");
    std::string out = (dir / "out.exr").string();
    CliRun r = cli("render '" SS_SOURCE_DIR "/examples/scenes/demo.json' --width 96 --height 72 -m auto -m shadow_map -o '" +
                   out + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("est.rmse"), std::string::npos) << r.out;
    auto in = OIIO::ImageInput::open(out);
    ASSERT_TRUE(in);
    const std::string estimates = in->spec().get_string_attribute(ss::kExrEstimatesAttribute);
    const std::vector<std::string> channels = in->spec().channelnames;
    in->close();
    // The report's passes are the EXR's own: auto's row names `Area_auto...`, beside the method
    // that ran; every pass it lists is a channel of the file.
    std::istringstream report(r.out);
    std::string line;
    bool sawAutoRow = false;
    while (std::getline(report, line)) {
        std::istringstream row(line);
        std::string light, asked, used, seconds, estimate, pass;
        if (!(row >> light >> asked >> used >> seconds >> estimate) || light != "Area") continue;
        std::vector<std::string> passes;
        while (row >> pass) passes.push_back(pass);
        if (asked == "auto") {
            sawAutoRow = true;
            EXPECT_NE(used, "auto") << line;
            ASSERT_GE(passes.size(), 2u) << line;
            EXPECT_EQ(passes[0], "Area_auto") << line;
            EXPECT_EQ(passes[1], "Area_auto_mask") << line;
            for (const std::string& p : passes) EXPECT_EQ(p.rfind("Area_auto", 0), 0u) << line;
        }
        for (const std::string& p : passes)
            EXPECT_NE(std::find(channels.begin(), channels.end(), "ViewLayer." + p + ".V"), channels.end())
                << p << " is printed but not in the EXR";
    }
    EXPECT_TRUE(sawAutoRow) << r.out;
    const double autoEstimate = estimateOf(estimates, "Area_auto");
    ASSERT_TRUE(std::isfinite(autoEstimate)) << estimates;
    EXPECT_TRUE(std::isnan(estimateOf(estimates, "Area_shadow_map"))) << estimates;  // none was asked for
    // The report's row for auto shows the same number the header keeps.
    char shown[32];
    std::snprintf(shown, sizeof shown, "%.4f", autoEstimate);
    EXPECT_NE(r.out.find(shown), std::string::npos) << r.out << " lacks " << shown;
    // `compare` sets auto's pass beside another method's (the names pair by light).
    CliRun c = cli("compare '" + out + "' --against shadow_map --json");
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_NE(c.out.find("Area_auto"), std::string::npos) << c.out;
    fs::remove_all(dir);
}

}  // namespace
