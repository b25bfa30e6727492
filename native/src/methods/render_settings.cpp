// How method settings are parsed from "key=value;..." and read with defaults.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "methods/method.h"

namespace ss {

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

namespace {

std::string shown(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

float RenderSettings::number(const std::string& key, float fallback) const {
    auto it = options.find(key);
    if (it == options.end()) return fallback;
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(it->second.c_str(), &end);
    if (end == it->second.c_str() || *end != '\0')
        fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + it->second + "' is not a number");
    if (!std::isfinite(v) || std::fabs(v) > double(std::numeric_limits<float>::max()))
        fail(SS_ERROR_INVALID_ARGUMENT,
             "setting '" + key + "' = '" + it->second + "' is not a finite number");
    return float(v);
}

float RenderSettings::number(const std::string& key, float fallback, float lo, float hi) const {
    float v = number(key, fallback);
    if (!(v >= lo && v <= hi))
        fail(SS_ERROR_INVALID_ARGUMENT, "setting '" + key + "' = '" + text(key, "") + "' is outside [" +
                                            shown(lo) + ", " + shown(hi) + "]");
    return v;
}

int RenderSettings::whole(const std::string& key, int fallback, int lo, int hi, bool orZero) const {
    if (options.find(key) == options.end()) return fallback;
    float v = number(key, float(fallback));
    std::string allowed = std::string(orZero ? "0 (the default) or " : "") + "a whole number in [" +
                          std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (v != std::floor(v) || !((v >= float(lo) && v <= float(hi)) || (orZero && v == 0.0f)))
        fail(SS_ERROR_INVALID_ARGUMENT,
             "setting '" + key + "' = '" + text(key, "") + "' is not " + allowed);
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

std::string RenderSettings::text(const std::string& key, const std::string& fallback) const {
    auto it = options.find(key);
    return it == options.end() ? fallback : it->second;
}

int shadowMapSizeSetting(const RenderSettings& settings) {
    return settings.whole("shadow_map_size", 0, 16, 8192, true);
}

void RenderSettings::report(float fraction, const char* stage) const {
    if (progress && !progress(fraction, stage))
        fail(SS_ERROR_CANCELLED, std::string("cancelled during ") + stage);
}

}  // namespace ss
