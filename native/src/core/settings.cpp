// How method settings are parsed from "key=value;...", checked against the method's keys and
// read with defaults and ranges.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/settings.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"

namespace ss {

namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? "none" : out;
}

std::string shown(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

std::map<std::string, std::string> parseSettings(const std::string& text) {
    std::map<std::string, std::string> out;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find(';', start);
        if (end == std::string::npos) end = text.size();
        std::string item = text.substr(start, end - start);
        if (!item.empty()) {
            size_t eq = item.find('=');
            if (eq == std::string::npos || eq == 0)
                fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + item + "' is not key=value");
            std::string key = item.substr(0, eq);
            if (out.count(key))
                fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' is given twice ('" + out[key] + "', '" +
                                                    item.substr(eq + 1) + "'); give it once");
            out[key] = item.substr(eq + 1);
        }
        start = end + 1;
    }
    return out;
}

float RenderSettings::number(const std::string& key, float fallback, float lo, float hi) const {
    auto it = options.find(key);
    if (it == options.end()) return fallback;
    const std::string& text = it->second;
    char* end = nullptr;
    errno = 0;
    float v = std::strtof(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0')
        fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + text + "' is not a number");
    if (!std::isfinite(v) || errno == ERANGE)
        fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + text + "' is not a finite number");
    if (v < lo || v > hi)
        fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + text + "' is out of range " +
                                            shown(lo) + ".." + shown(hi));
    return v;
}

int RenderSettings::integer(const std::string& key, int fallback, int lo, int hi) const {
    auto it = options.find(key);
    if (it == options.end()) return fallback;
    float v = number(key, float(fallback));
    if (v != std::floor(v))
        fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + it->second + "' is not a whole number");
    if (v < float(lo) || v > float(hi))
        fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + it->second + "' is out of range " +
                                            std::to_string(lo) + ".." + std::to_string(hi));
    return int(v);
}

bool RenderSettings::flag(const std::string& key, bool fallback) const {
    auto it = options.find(key);
    if (it == options.end()) return fallback;
    const std::string& v = it->second;
    if (v == "1" || v == "true" || v == "on" || v == "yes") return true;
    if (v == "0" || v == "false" || v == "off" || v == "no") return false;
    fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + v + "' is not on/off");
}

std::string RenderSettings::choice(const std::string& key, const std::string& fallback,
                                   const std::vector<std::string>& allowed) const {
    auto it = options.find(key);
    if (it == options.end()) return fallback;
    for (const std::string& a : allowed)
        if (it->second == a) return it->second;
    fail(SS_ERROR_INVALID_ARGUMENT,
         "setting '" + key + "' = '" + it->second + "' is not one of: " + joined(allowed));
}

float RenderSettings::number(const SettingSpec& spec) const {
    return number(spec.key, float(spec.fallback), float(spec.lo), float(spec.hi));
}

int RenderSettings::integer(const SettingSpec& spec) const { return integer(spec, int(spec.fallback)); }

int RenderSettings::integer(const SettingSpec& spec, int fallback) const {
    if (spec.zeroIsDefault) {
        auto it = options.find(spec.key);
        if (it == options.end()) return fallback;
        const float v = number(spec.key, 0.0f);  // refuses nan and inf first
        if (v != std::floor(v) || !(v == 0.0f || (v >= float(spec.lo) && v <= float(spec.hi))))
            fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + std::string(spec.key) + "' = '" + it->second +
                                                "' is out of range " + spec.rangeText());
        return int(v);
    }
    return integer(spec.key, fallback, int(spec.lo), int(spec.hi));
}

bool RenderSettings::flag(const SettingSpec& spec) const { return flag(spec.key, spec.fallback != 0.0); }

std::string RenderSettings::choice(const SettingSpec& spec) const {
    return choice(spec.key, spec.defaultText(), spec.choiceList());
}

std::string RenderSettings::text(const SettingSpec& spec) const {
    auto it = options.find(spec.key);
    return it == options.end() ? std::string() : it->second;
}

int shadowMapSizeSetting(const RenderSettings& settings) { return settings.integer(kShadowMapSizeSetting); }

void RenderSettings::requireKnownKeys(const std::string& method, const SettingTable& table) const {
    for (const auto& [key, value] : options) {
        const SettingSpec* spec = findSetting(table, key);
        if (!spec)
            fail(SS_ERROR_INVALID_ARGUMENT, "method '" + method + "' has no setting '" + key +
                                                "' (its settings: " + joined(userKeys(table)) + ")");
        switch (spec->type) {
            case SettingType::Int: (void)integer(*spec); break;
            case SettingType::Float: (void)number(*spec); break;
            case SettingType::Bool: (void)flag(*spec); break;
            case SettingType::Choice: (void)choice(*spec); break;
            case SettingType::Text: break;
        }
    }
}

void RenderSettings::checkCancelled(const char* stage) const {
    if (cancel && cancel->load(std::memory_order_relaxed))
        fail(SS_ERROR_CANCELLED, std::string("cancelled during ") + stage);
}

void RenderSettings::report(float fraction, const char* stage) const {
    checkCancelled(stage);
    if (progress && !progress(fraction, stage))
        fail(SS_ERROR_CANCELLED, std::string("cancelled during ") + stage);
}

}  // namespace ss
