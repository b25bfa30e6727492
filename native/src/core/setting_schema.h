// The schema of the "key=value" settings: one typed entry per key (type, default, range, doc),
// from which the reader, the unknown-key error, the C API's list and the docs check all come.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <vector>

namespace ss {

enum class SettingType { Int, Float, Bool, Choice, Text };

// One key. Keys starting with "debug." are test switches: accepted, but left out of every list a
// user sees (the unknown-key error, ss_method_setting_info, the docs' tables).
struct SettingSpec {
    const char* key = "";
    SettingType type = SettingType::Text;
    double fallback = 0.0;      // Int, Float, Bool (0/1): the default
    double lo = 0.0, hi = 0.0;  // Int, Float: the range, both ends included
    const char* choices = "";   // Choice: the allowed words, "a|b|c"; its default is the first
    const char* doc = "";       // one line for the user; names a default that depends on the render
    bool zeroIsDefault = false;  // Int: 0 is accepted besides [lo, hi] and means "the default"
    // A default the render decides (the reader is given it), as shown to users; null: `fallback`.
    const char* renderDefault = nullptr;

    bool debug() const { return std::string(key).rfind("debug.", 0) == 0; }
    // The default as a user writes it ("8", "off", "sat"), or renderDefault; "" for Text.
    std::string defaultText() const;
    // "1..16", "0..0.5", "on/off", "sat|mipmap|nbuffer", "0 or 16..8192", "" for Text.
    std::string rangeText() const;
    std::vector<std::string> choiceList() const;
};

constexpr SettingSpec intSetting(const char* key, int fallback, int lo, int hi, const char* doc) {
    return {key, SettingType::Int, double(fallback), double(lo), double(hi), "", doc};
}
constexpr SettingSpec floatSetting(const char* key, double fallback, double lo, double hi, const char* doc) {
    return {key, SettingType::Float, fallback, lo, hi, "", doc};
}
constexpr SettingSpec flagSetting(const char* key, bool fallback, const char* doc) {
    return {key, SettingType::Bool, fallback ? 1.0 : 0.0, 0.0, 1.0, "", doc};
}
// `choices`: "default|other|..."
constexpr SettingSpec choiceSetting(const char* key, const char* choices, const char* doc) {
    return {key, SettingType::Choice, 0.0, 0.0, 0.0, choices, doc};
}
constexpr SettingSpec textSetting(const char* key, const char* doc) {
    return {key, SettingType::Text, 0.0, 0.0, 0.0, "", doc};
}

using SettingTable = std::vector<SettingSpec>;

// `table` followed by the entries of `more` whose keys it does not have yet.
SettingTable composed(SettingTable table, const SettingTable& more);
// The entry for `key`, or null.
const SettingSpec* findSetting(const SettingTable& table, const std::string& key);
// The keys a user may give (debug ones left out), in table order.
std::vector<std::string> userKeys(const SettingTable& table);

// The shared shadow map's size, taken by every method that draws one: 0 (the frame's default)
// or 16..8192.
inline constexpr SettingSpec kShadowMapSizeSetting{
    "shadow_map_size", SettingType::Int, 0.0, 16.0, 8192.0, "",
    "side of the shared shadow map in texels (0: the frame's default, 2048)", true};

}  // namespace ss
