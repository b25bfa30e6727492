// How the C API turns ss_render_options into RenderSettings, and lists a method's settings.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <map>
#include <memory>
#include <mutex>

#include "capi/capi_internal.h"

namespace ss::capi {

ss::RenderSettings renderSettingsFrom(const ss_render_options* options, const char* function,
                                      const std::atomic<bool>* cancel) {
    ss_render_options o;
    ss_render_options_default(&o);
    if (options) o = *options;
    const std::string in = std::string(function) + ": ";
    if (o.samples < 0)
        ss::fail(SS_ERROR_INVALID_ARGUMENT,
                 in + "samples must not be negative (got " + std::to_string(o.samples) + ")");
    if (o.refine != SS_REFINE_OFF && o.refine != SS_REFINE_ON)
        ss::fail(SS_ERROR_INVALID_ARGUMENT, in + "refine must be SS_REFINE_OFF or SS_REFINE_ON (got " +
                                                std::to_string(int(o.refine)) + ")");
    if (o.refine_rounds < 0 || o.refine_rounds > 64)
        ss::fail(SS_ERROR_INVALID_ARGUMENT,
                 in + "refine_rounds must be in 0..64 (got " + std::to_string(o.refine_rounds) + ")");
    ss::RenderSettings s;
    s.samples = o.samples;
    s.refine = o.refine == SS_REFINE_ON;
    s.refineRounds = o.refine_rounds > 0 ? o.refine_rounds : 1;
    s.seed = o.seed;
    s.extraLayers = o.extra_layers != 0;
    if (o.settings) s.options = ss::parseSettings(o.settings);
    if (o.progress) {
        ss_progress_fn fn = o.progress;
        void* user = o.progress_user;
        s.progress = [fn, user](float fraction, const char* stage) {
            ProgressCallbackScope inside;
            return fn(user, fraction, stage ? stage : "") == 0;
        };
    }
    s.cancel = cancel;
    return s;
}

}  // namespace ss::capi

namespace {

const char* typeName(ss::SettingType type) {
    switch (type) {
        case ss::SettingType::Int: return "int";
        case ss::SettingType::Float: return "float";
        case ss::SettingType::Bool: return "bool";
        case ss::SettingType::Choice: return "choice";
        case ss::SettingType::Text: return "text";
    }
    return "text";
}

// The strings ss_setting_info points at: made once per method and kept for the process's life.
struct ListedSetting {
    std::string key, type, fallback, range, doc;
};

const std::vector<ListedSetting>& listedSettings(const std::string& method) {
    static std::mutex m;
    static std::map<std::string, std::unique_ptr<std::vector<ListedSetting>>> lists;
    std::lock_guard lock(m);
    auto it = lists.find(method);
    if (it != lists.end()) return *it->second;
    auto list = std::make_unique<std::vector<ListedSetting>>();
    for (const ss::SettingSpec& s : ss::renderSettingTable(method))
        if (!s.debug()) list->push_back({s.key, typeName(s.type), s.defaultText(), s.rangeText(), s.doc});
    return *lists.emplace(method, std::move(list)).first->second;
}

}  // namespace

extern "C" {

SS_API int32_t ss_method_setting_count(const char* method) {
    int32_t count = -1;
    ss::capi::guarded([&] {
        ss::capi::require(method, "ss_method_setting_count", "method");
        count = int32_t(listedSettings(method).size());
    });
    return count;
}

SS_API ss_status ss_method_setting_info(const char* method, int32_t index, ss_setting_info* out) {
    return ss::capi::guarded([&] {
        ss::capi::require(method, "ss_method_setting_info", "method");
        ss::capi::require(out, "ss_method_setting_info", "out");
        const std::vector<ListedSetting>& list = listedSettings(method);
        if (index < 0 || size_t(index) >= list.size())
            ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_method_setting_info: index " + std::to_string(index) +
                                                    " is out of range (method '" + method + "' has " +
                                                    std::to_string(list.size()) + " settings)");
        const ListedSetting& s = list[size_t(index)];
        *out = ss_setting_info{s.key.c_str(), s.type.c_str(), s.fallback.c_str(), s.range.c_str(), s.doc.c_str()};
    });
}

}  // extern "C"
