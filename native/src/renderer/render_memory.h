// Whether a render fits the memory budget (core/memory_budget.h), checked before any work.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

#include "core/memory_budget.h"
#include "core/scene.h"
#include "core/settings.h"

namespace ss {

// The setting every method (and auto) takes: the memory a render may need, in MiB; 0 (the
// default): the machine's physical memory.
inline constexpr SettingSpec kMemoryLimitSetting = intSetting(
    "memory_limit_mb", 0, 0, 1 << 24, "memory a render may need, in MiB (0: the machine's physical memory)");

// Takes kMemoryLimitSetting out of `settings` and leaves the limit it gives in
// settings.memoryLimit (what the sweep's shadow mesh is checked against).
MemoryLimit takeMemoryLimit(RenderSettings& settings);
// takeMemoryLimit, then throws ss::Error(SS_ERROR_INVALID_ARGUMENT) when
// the render's budget (renderPeakBytes) is over the limit, with both figures in the message.
void checkRenderMemory(const Scene& scene, int lightIndex, const std::string& method, RenderSettings& settings);

}  // namespace ss
