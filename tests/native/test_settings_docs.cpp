// Do the C API's setting lists, docs/settings.md and the method pages say the same keys?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "softshadow/softshadow.h"

namespace {

std::vector<std::string> methodsAndAuto() {
    std::vector<std::string> out;
    for (int32_t i = 0; i < ss_method_count(); ++i) out.push_back(ss_method_name(i));
    out.push_back("auto");
    return out;
}

std::vector<ss_setting_info> settingsOf(const std::string& method) {
    std::vector<ss_setting_info> out;
    const int32_t n = ss_method_setting_count(method.c_str());
    for (int32_t i = 0; i < n; ++i) {
        ss_setting_info info{};
        EXPECT_EQ(ss_method_setting_info(method.c_str(), i, &info), SS_OK) << ss_last_error();
        out.push_back(info);
    }
    return out;
}

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// A choice's "a|b" as a table cell can hold it.
std::string cellText(std::string text) {
    for (size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at)) text.replace(at, 1, ", ");
    return text;
}

// docs/settings.md as the tables make it.
std::string settingsPage() {
    std::string page =
        "# Settings of each method\n\n"
        "What `Method Settings` (the add-on), `--set key=value` (the CLI) and `ss_render_options.settings`\n"
        "(the C API) accept, per method: made from the library's tables (`ss_method_setting_info`) and\n"
        "checked by the test `SettingsDocs.TheSettingsPageIsTheLibrarysTables`; regenerate it with\n"
        "`SS_UPDATE_DOCS=1 build/softshadow_tests --gtest_filter=SettingsDocs.*`. A key not in its method's\n"
        "table, or a value outside its range, is refused naming the key, the value and the range. `auto`\n"
        "takes its own keys and every candidate method's: each candidate it renders gets the keys its\n"
        "method has. Whether to refine is no key: `ss_render_options.refine`, the CLI's `--refine`, the\n"
        "add-on's Refine Final Renders.\n";
    for (const std::string& method : methodsAndAuto()) {
        page += "\n## " + method + "\n\n| key | type | default | range | what it does |\n|---|---|---|---|---|\n";
        for (const ss_setting_info& s : settingsOf(method))
            page += std::string("| `") + s.key + "` | " + s.type + " | " + (*s.default_value ? s.default_value : "-") +
                    " | " + (*s.range ? cellText(s.range) : "-") + " | " + s.doc + " |\n";
    }
    return page;
}

TEST(SettingsDocs, TheSettingsPageIsTheLibrarysTables) {
    const std::string path = std::string(SS_SOURCE_DIR) + "/docs/settings.md";
    const std::string expected = settingsPage();
    if (std::getenv("SS_UPDATE_DOCS")) std::ofstream(path) << expected;
    EXPECT_EQ(readText(path), expected) << "docs/settings.md is not what the tables say; regenerate it";
}

bool listed(const std::vector<ss_setting_info>& list, const std::string& key) {
    for (const ss_setting_info& s : list)
        if (key == s.key) return true;
    return false;
}

TEST(SettingsDocs, EveryKeyIsOnItsMethodsPage) {
    // The keys every method takes are documented once, in docs/methods/README.md (with auto's
    // own); a method's own keys on its page (auto's candidates' keys on the candidate's).
    const std::string readme = readText(std::string(SS_SOURCE_DIR) + "/docs/methods/README.md");
    for (const std::string& method : methodsAndAuto()) {
        for (const ss_setting_info& s : settingsOf(method)) {
            bool everyMethods = true;
            std::string owner = method;
            for (int32_t i = 0; i < ss_method_count(); ++i) {
                const bool has = listed(settingsOf(ss_method_name(i)), s.key);
                everyMethods = everyMethods && has;
                if (method == "auto" && has && owner == "auto") owner = ss_method_name(i);
            }
            const std::string where =
                everyMethods || owner == "auto"
                    ? readme
                    : readText(std::string(SS_SOURCE_DIR) + "/docs/methods/" + owner + ".md");
            EXPECT_NE(where.find(std::string("`") + s.key), std::string::npos)
                << method << ": `" << s.key << "` is not on " << owner << "'s page";
        }
    }
}

TEST(SettingsDocs, TestSwitchesAreAcceptedButNeverListed) {
    for (const std::string& method : methodsAndAuto())
        for (const ss_setting_info& s : settingsOf(method))
            EXPECT_NE(std::string(s.key).rfind("debug.", 0), 0u) << method << " lists " << s.key;
    EXPECT_EQ(readText(std::string(SS_SOURCE_DIR) + "/docs/settings.md").find("debug."), std::string::npos);
}

TEST(CApiSettings, AMethodsSettingsAreListedWithTypeDefaultRangeAndDoc) {
    std::vector<ss_setting_info> pcss = settingsOf("pcss");
    ASSERT_GE(pcss.size(), 4u);
    EXPECT_STREQ(pcss[0].key, "blocker_samples");
    EXPECT_STREQ(pcss[0].type, "int");
    EXPECT_STREQ(pcss[0].default_value, "16");
    EXPECT_STREQ(pcss[0].range, "1..1024");
    EXPECT_GT(std::string(pcss[0].doc).size(), 5u);
    std::vector<ss_setting_info> ot = settingsOf("occlusion_textures");
    ASSERT_FALSE(ot.empty());
    bool filter = false, refine = false, margin = false;
    for (const ss_setting_info& s : ot) {
        if (std::string(s.key) == "filter") {
            filter = true;
            EXPECT_STREQ(s.range, "sat|mipmap|nbuffer");
            EXPECT_STREQ(s.default_value, "sat");
        }
        // Whether to refine is ss_render_options.refine; the keys tune it.
        refine =
            refine || std::string(s.key).rfind("refine", 0) == 0 && std::string(s.key) != "refine_margin" &&
                          std::string(s.key) != "refine_samples" && std::string(s.key) != "refine_verify";
        if (std::string(s.key) == "refine_margin") {
            margin = true;
            EXPECT_STREQ(s.default_value, "3");
        }
    }
    EXPECT_TRUE(filter);
    EXPECT_FALSE(refine);
    EXPECT_TRUE(margin);
    EXPECT_EQ(ss_method_setting_count("no_such_method"), -1);
    EXPECT_NE(std::string(ss_last_error()).find("no_such_method"), std::string::npos);
    ss_setting_info info{};
    EXPECT_EQ(ss_method_setting_info("pcss", int32_t(pcss.size()), &info), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_method_setting_info("pcss", -1, &info), SS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ss_method_setting_info("pcss", 0, nullptr), SS_ERROR_INVALID_ARGUMENT);
}

}  // namespace
