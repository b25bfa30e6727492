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
        fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + text + "' is out of range [" +
                                            shown(lo) + ", " + shown(hi) + "]");
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
                                   std::initializer_list<const char*> allowed) const {
    auto it = options.find(key);
    if (it == options.end()) return fallback;
    std::vector<std::string> names;
    for (const char* a : allowed) {
        if (it->second == a) return it->second;
        names.push_back(a);
    }
    fail(SS_ERROR_INVALID_ARGUMENT,
         "setting '" + key + "' = '" + it->second + "' is not one of: " + joined(names));
}

std::string RenderSettings::text(const std::string& key, const std::string& fallback) const {
    auto it = options.find(key);
    return it == options.end() ? fallback : it->second;
}

int shadowMapSizeSetting(const RenderSettings& settings) {
    const float size = settings.number("shadow_map_size", 0.0f);  // refuses nan and inf first
    if (size != std::floor(size) || !(size == 0.0f || (size >= 16.0f && size <= 8192.0f)))
        fail(SS_ERROR_INVALID_ARGUMENT, "setting 'shadow_map_size' = '" + settings.text("shadow_map_size", "") +
                                            "' is not 0 (the default) or a whole number in [16, 8192]");
    return int(size);
}

void RenderSettings::requireKnownKeys(const std::string& method, const std::vector<std::string>& known) const {
    for (const auto& [key, value] : options) {
        bool found = false;
        for (const std::string& k : known) found = found || k == key;
        if (!found)
            fail(SS_ERROR_INVALID_ARGUMENT, "method '" + method + "' has no setting '" + key +
                                                "' (its settings: " + joined(known) + ")");
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
