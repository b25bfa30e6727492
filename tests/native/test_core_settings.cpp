// Does the one settings reader parse, range-check and refuse unknown keys with clear messages?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/settings.h"

namespace ss {
namespace {

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_INVALID_ARGUMENT);
        return e.what();
    }
    return "";
}

RenderSettings with(const std::string& text) {
    RenderSettings s;
    s.options = parseSettings(text);
    return s;
}

TEST(Settings, TypedGettersReadValuesAndDefaults) {
    RenderSettings s = with("a=2.5;n=12;f=on;c=sat");
    EXPECT_EQ(s.number("a", 0.0f), 2.5f);
    EXPECT_EQ(s.number("missing", 7.0f), 7.0f);
    EXPECT_EQ(s.integer("n", 0, 1, 16), 12);
    EXPECT_EQ(s.integer("missing", 8, 1, 16), 8);
    EXPECT_TRUE(s.flag("f", false));
    EXPECT_EQ(s.choice("c", "mipmap", {"mipmap", "sat"}), "sat");
}

TEST(Settings, BadValuesAreRefusedNamingTheKey) {
    EXPECT_EQ(errorOf([] { with("bias=nan").number("bias", 1.0f); }), "setting 'bias' = 'nan' is not a finite number");
    EXPECT_EQ(errorOf([] { with("bias=inf").number("bias", 1.0f); }), "setting 'bias' = 'inf' is not a finite number");
    EXPECT_EQ(errorOf([] { with("bias=1e99").number("bias", 1.0f); }), "setting 'bias' = '1e99' is not a finite number");
    EXPECT_EQ(errorOf([] { with("bias=x").number("bias", 1.0f); }), "setting 'bias' = 'x' is not a number");
    EXPECT_EQ(errorOf([] { with("n=2.5").integer("n", 1, 1, 16); }), "setting 'n' = '2.5' is not a whole number");
    EXPECT_EQ(errorOf([] { with("n=17").integer("n", 1, 1, 16); }), "setting 'n' = '17' is out of range 1..16");
    EXPECT_EQ(errorOf([] { with("c=box").choice("c", "sat", {"mipmap", "sat"}); }),
              "setting 'c' = 'box' is not one of: mipmap, sat");
    EXPECT_EQ(errorOf([] { with("f=maybe").flag("f", false); }), "setting 'f' = 'maybe' is not on/off");
    EXPECT_NE(errorOf([] { with("x=0.5").number("x", 0.0f, 1.0f, 2.0f); }).find("out of range"), std::string::npos);
    EXPECT_EQ(errorOf([] { parseSettings("novalue"); }), "setting 'novalue' is not key=value");
}

const SettingTable kTable{intSetting("blocker_samples", 16, 1, 1024, "taps"),
                          intSetting("pcf_samples", 32, 1, 4096, "taps"),
                          flagSetting("debug.finish_stages", false, "glFinish")};

TEST(Settings, UnknownKeysAreRefusedListingTheUserKeysOfTheTable) {
    EXPECT_EQ(errorOf([] { with("blocker_sample=64").requireKnownKeys("pcss", kTable); }),
              "method 'pcss' has no setting 'blocker_sample' (its settings: blocker_samples, pcf_samples)");
    EXPECT_EQ(errorOf([] { with("x=1").requireKnownKeys("m", {}); }), "method 'm' has no setting 'x' (its settings: none)");
    EXPECT_EQ(errorOf([] { with("pcf_samples=4").requireKnownKeys("pcss", kTable); }), "");
    // A test switch is accepted under its debug. name only, and never listed.
    EXPECT_EQ(errorOf([] { with("debug.finish_stages=1").requireKnownKeys("pcss", kTable); }), "");
    EXPECT_NE(errorOf([] { with("finish_stages=1").requireKnownKeys("pcss", kTable); }), "");
    EXPECT_EQ(userKeys(kTable), (std::vector<std::string>{"blocker_samples", "pcf_samples"}));
}

TEST(Settings, TheTableGivesDefaultAndRangeAndEveryValueIsCheckedUpFront) {
    const SettingSpec slices = intSetting("slices", 8, 1, 16, "slices");
    const SettingSpec filter = choiceSetting("filter", "sat|mipmap|nbuffer", "filter");
    const SettingSpec border = floatSetting("border", 0.25, 0.0, 1.0, "share");
    const SettingSpec thin = flagSetting("thin_fix", false, "fix");
    EXPECT_EQ(with("").integer(slices), 8);
    EXPECT_EQ(with("slices=3").integer(slices), 3);
    EXPECT_EQ(with("").choice(filter), "sat");
    EXPECT_EQ(with("filter=nbuffer").choice(filter), "nbuffer");
    EXPECT_EQ(with("").number(border), 0.25f);
    EXPECT_FALSE(with("").flag(thin));
    EXPECT_EQ(slices.defaultText(), "8");
    EXPECT_EQ(slices.rangeText(), "1..16");
    EXPECT_EQ(filter.defaultText(), "sat");
    EXPECT_EQ(thin.defaultText(), "off");
    EXPECT_EQ(kShadowMapSizeSetting.rangeText(), "0 or 16..8192");
    // A value out of range names the key, the value and the range, before any read.
    const SettingTable table{slices, filter, border, thin, kShadowMapSizeSetting};
    EXPECT_EQ(errorOf([&] { with("slices=17").requireKnownKeys("m", table); }), "setting 'slices' = '17' is out of range 1..16");
    EXPECT_EQ(errorOf([&] { with("border=2").requireKnownKeys("m", table); }), "setting 'border' = '2' is out of range 0..1");
    EXPECT_EQ(errorOf([&] { with("filter=box").requireKnownKeys("m", table); }),
              "setting 'filter' = 'box' is not one of: sat, mipmap, nbuffer");
    EXPECT_EQ(errorOf([&] { with("shadow_map_size=8").requireKnownKeys("m", table); }),
              "setting 'shadow_map_size' = '8' is out of range 0 or 16..8192");
    EXPECT_EQ(with("shadow_map_size=0").integer(kShadowMapSizeSetting), 0);
    EXPECT_EQ(with("shadow_map_size=512").integer(kShadowMapSizeSetting), 512);
    EXPECT_EQ(composed(table, {slices, intSetting("extra", 0, 0, 1, "")}).size(), table.size() + 1);
}

}  // namespace
}  // namespace ss
