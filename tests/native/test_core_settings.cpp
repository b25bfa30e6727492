// Does the one settings reader parse, range-check and refuse unknown keys with clear messages?
// SPDX-License-Identifier: GPL-3.0-or-later
#include <functional>
#include <string>

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

TEST(Settings, UnknownKeysAreRefusedListingTheKnownOnes) {
    EXPECT_EQ(errorOf([] { with("blocker_sample=64").requireKnownKeys("pcss", {"blocker_samples", "pcf_samples"}); }),
              "method 'pcss' has no setting 'blocker_sample' (its settings: blocker_samples, pcf_samples)");
    EXPECT_EQ(errorOf([] { with("x=1").requireKnownKeys("m", {}); }), "method 'm' has no setting 'x' (its settings: none)");
    EXPECT_EQ(errorOf([] { with("pcf_samples=4").requireKnownKeys("pcss", {"blocker_samples", "pcf_samples"}); }), "");
}

}  // namespace
}  // namespace ss
