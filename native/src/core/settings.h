// What a render is asked for beyond (scene, light, method): samples, seed, layers, refinement,
// the method's own settings ("key=value") and the progress callback, and how those settings are read.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "core/setting_schema.h"

namespace ss {

// What a render may take (core/memory_budget.h): `bytes` 0 is unchecked; from the setting
// memory_limit_mb, or the machine's memory (renderer/render_memory.h works it out before a render).
struct MemoryLimit {
    double bytes = 0.0;
    bool fromSetting = false;
};

// Returns false to cancel. fraction in [0,1].
using ProgressFn = std::function<bool(float fraction, const char* stage)>;

struct RenderSettings {
    int samples = 0;  // 0 = the method's default
    uint32_t seed = 1;
    bool extraLayers = true;
    std::map<std::string, std::string> options;  // method quality settings, "key" -> "value"
    // Re-trace a GL method's uncertain pixels with rays (renderer/refinement.h), in this many
    // shares (1..64).
    bool refine = false;
    int refineRounds = 1;
    ProgressFn progress;
    // Set by the owner of the render (ss_context_destroy) to stop it at the next check; null: never.
    const std::atomic<bool>* cancel = nullptr;
    // What the render may take (renderer/render_memory.h sets it before any work; 0: unchecked).
    MemoryLimit memoryLimit;

    // Reads `spec.key` from `options` as the table entry says: its default when absent; a
    // malformed, non-finite or out-of-range value throws ss::Error(SS_ERROR_INVALID_ARGUMENT)
    // naming the key, the value and the range. The second integer form takes a default that
    // depends on the render (the entry's doc names it).
    float number(const SettingSpec& spec) const;
    int integer(const SettingSpec& spec) const;
    int integer(const SettingSpec& spec, int fallback) const;
    bool flag(const SettingSpec& spec) const;
    std::string choice(const SettingSpec& spec) const;
    std::string text(const SettingSpec& spec) const;

    // The parsing under the readers above, for a key without an entry.
    float number(const std::string& key, float fallback,
                 float lo = -std::numeric_limits<float>::max(),
                 float hi = std::numeric_limits<float>::max()) const;
    int integer(const std::string& key, int fallback, int lo, int hi) const;
    bool flag(const std::string& key, bool fallback) const;
    // One of `allowed`.
    std::string choice(const std::string& key, const std::string& fallback,
                       const std::vector<std::string>& allowed) const;

    // Throws ss::Error(SS_ERROR_INVALID_ARGUMENT) naming the first key of `options` that is not
    // in `table`, listing the table's user keys (a typo must not render the default silently),
    // or the first value its entry refuses: every given value is checked before any work.
    void requireKnownKeys(const std::string& method, const SettingTable& table) const;

    // Calls progress; throws ss::Error(SS_ERROR_CANCELLED) when it asks to stop.
    void report(float fraction, const char* stage) const;
    // Throws ss::Error(SS_ERROR_CANCELLED) when `cancel` is set: cheap and thread-safe, for the
    // loops of CPU stages (they poll it between items without reporting progress).
    void checkCancelled(const char* stage) const;
};

// The shared shadow map's size (kShadowMapSizeSetting).
int shadowMapSizeSetting(const RenderSettings& settings);

// Parses "key=value;key=value" (the C API's settings string).
std::map<std::string, std::string> parseSettings(const std::string& text);

}  // namespace ss
