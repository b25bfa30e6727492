// Checks, through the C API, that `auto` hands each candidate the user's settings its method has,
// and refuses a key no candidate has.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "capi_demo.h"
#include "softshadow/softshadow.h"

namespace {

struct Demo : test::CapiDemo {
    Demo() : CapiDemo(96, 72) {}

    struct Pass {
        ss_status status = SS_OK;
        std::string method, error;
        std::vector<float> v;
    };
    Pass render(const char* method, const char* settings) const {
        ss_render_options o;
        ss_render_options_default(&o);
        o.settings = settings;
        ss_result* result = nullptr;
        Pass out;
        out.status = ss_render(context, scene, 0, method, &o, &result);
        if (out.status != SS_OK) {
            out.error = ss_last_error();
            return out;
        }
        out.method = ss_result_method(result);
        for (int32_t i = 0; i < ss_result_layer_count(result); ++i) {
            const char* name = nullptr;
            const float* pixels = nullptr;
            int32_t w = 0, h = 0;
            EXPECT_EQ(ss_result_layer(result, i, &name, &pixels, &w, &h), SS_OK);
            if (std::strcmp(name, "V") == 0) out.v.assign(pixels, pixels + size_t(w) * size_t(h));
        }
        ss_result_destroy(result);
        return out;
    }
};

// Without the sparse check auto takes dbuffer for the demo's disk light: a dbuffer key changes
// auto's pass as it changes dbuffer's, and a pcss key given beside it does not reach dbuffer.
TEST(AutoSettings, TheChosenCandidateTakesTheKeysItsMethodHas) {
    Demo d;
    const Demo::Pass plain = d.render("auto", "check_pixels=0");
    ASSERT_EQ(plain.status, SS_OK) << plain.error;
    ASSERT_EQ(plain.method, "dbuffer");
    const Demo::Pass segment = d.render("auto", "check_pixels=0;profile=segment;blocker_samples=4");
    ASSERT_EQ(segment.status, SS_OK) << segment.error;
    EXPECT_EQ(segment.method, "dbuffer");
    EXPECT_NE(segment.v, plain.v) << "profile=segment did not reach dbuffer";
    EXPECT_EQ(segment.v, d.render("dbuffer", "profile=segment").v);
    EXPECT_EQ(plain.v, d.render("dbuffer", nullptr).v);
}

// With the sparse check: the candidate auto measures and keeps renders with the user's key of
// its method (each method's key below changes its pass), so auto's pass is that method's with it.
TEST(AutoSettings, TheMeasuredChoiceRendersWithTheUsersSettings) {
    Demo d;
    const Demo::Pass plain = d.render("auto", nullptr);
    ASSERT_EQ(plain.status, SS_OK) << plain.error;
    const std::map<std::string, std::string> keyOf{
        {"shadow_map", "bias=20"},           {"pcss", "blocker_samples=1"},
        {"dbuffer", "profile=segment"},      {"sweep", "fill=rings"},
        {"penumbra_map", "intensity=paper"}, {"occlusion_textures", "resolution=64"}};
    ASSERT_TRUE(keyOf.count(plain.method)) << plain.method;
    const std::string key = keyOf.at(plain.method);
    const Demo::Pass keyed = d.render("auto", key.c_str());
    ASSERT_EQ(keyed.status, SS_OK) << keyed.error;
    std::printf("auto took %s, with %s %s\n", plain.method.c_str(), key.c_str(), keyed.method.c_str());
    ASSERT_EQ(keyed.method, plain.method) << key << " moved the choice";
    EXPECT_NE(keyed.v, plain.v) << key << " did not reach " << plain.method;
    EXPECT_EQ(keyed.v, d.render(plain.method.c_str(), key.c_str()).v);
    EXPECT_EQ(plain.v, d.render(plain.method.c_str(), nullptr).v);
}

// A key of no candidate (the reference's own) is refused naming it; a value out of its method's
// range is refused before any work, naming the key, as for that method.
TEST(AutoSettings, AKeyNoCandidateHasIsRefusedNamingIt) {
    Demo d;
    for (const char* key : {"adaptive", "threads", "no_such_key"}) {
        const Demo::Pass bad = d.render("auto", (std::string(key) + "=1").c_str());
        EXPECT_EQ(bad.status, SS_ERROR_INVALID_ARGUMENT) << key;
        EXPECT_NE(bad.error.find("method 'auto' has no setting '" + std::string(key) + "'"),
                  std::string::npos)
            << bad.error;
    }
    const Demo::Pass range = d.render("auto", "blocker_samples=0");
    EXPECT_EQ(range.status, SS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(range.error.find("blocker_samples"), std::string::npos) << range.error;
}

// auto lists its own keys, then every candidate's once: a key several methods take means the
// same in each (type, default, range), so auto's one entry checks it for all of them.
TEST(AutoSettings, AutoListsEveryCandidatesKeysAndSharedKeysAgree) {
    std::map<std::string, std::vector<std::string>> seen;  // key -> type, default, range
    std::vector<std::string> autoKeys;
    for (int32_t i = 0; i < ss_method_setting_count("auto"); ++i) {
        ss_setting_info info{};
        ASSERT_EQ(ss_method_setting_info("auto", i, &info), SS_OK);
        autoKeys.push_back(info.key);
    }
    for (int32_t m = 0; m < ss_method_count(); ++m) {
        const std::string method = ss_method_name(m);
        for (int32_t i = 0; i < ss_method_setting_count(method.c_str()); ++i) {
            ss_setting_info info{};
            ASSERT_EQ(ss_method_setting_info(method.c_str(), i, &info), SS_OK);
            const std::vector<std::string> spec{info.type, info.default_value, info.range};
            auto [it, fresh] = seen.emplace(info.key, spec);
            EXPECT_TRUE(fresh || it->second == spec) << "'" << info.key << "' differs in " << method;
            const bool listed = std::count(autoKeys.begin(), autoKeys.end(), std::string(info.key)) == 1;
            EXPECT_EQ(listed, method != "reference" || std::string(info.key) == "error_target" ||
                                  std::string(info.key) == "guard_band" ||
                                  std::string(info.key).rfind("refine", 0) == 0 ||
                                  std::string(info.key) == "estimate_rmse" ||
                                  std::string(info.key) == "memory_limit_mb")
                << method << " " << info.key;
        }
    }
    EXPECT_EQ(autoKeys[0], "check_pixels");
    EXPECT_EQ(autoKeys[1], "check_samples");
}

}  // namespace
