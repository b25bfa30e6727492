// The renderer's cache counters as one struct and as a table by name (the C API's ss_cache_stat_*).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <iterator>

#include "scene_cache/cache_counters.h"

namespace ss {

// Over a renderer's life: its frames' SceneCacheStats and methods' MethodStats added up, and its own
// counters (scene_cache/cache_counters.h lists them all).
struct CacheStats {
    SS_CACHE_COUNTERS(SS_COUNTER_MEMBER)
};

// One counter by name: what it counts, and its value in a CacheStats (counts are exact in a double).
struct CacheStatInfo {
    const char* name;
    const char* doc;
    double (*value)(const CacheStats&);
};

#define SS_COUNTER_INFO(type, member, name, combine, doc) \
    CacheStatInfo{name, doc, [](const CacheStats& s) { return double(s.member); }},
inline constexpr CacheStatInfo kCacheStats[] = {SS_CACHE_COUNTERS(SS_COUNTER_INFO)};
#undef SS_COUNTER_INFO
inline constexpr size_t kCacheStatCount = std::size(kCacheStats);

}  // namespace ss
