// How the reference's CPU work is shared by the cores: rows taken from a counter.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>

#include "core/settings.h"

namespace ss {

inline constexpr SettingSpec kThreadsSetting =
    intSetting("threads", 0, 0, 1024, "worker threads (0: all cores); changes speed only");

// Runs rowFn(y) for every y in [0, rows) on the option "threads" workers (default: all cores).
// The calling thread only reports progress (`stage`, fraction in [progressFrom, progressTo]),
// so the progress callback (which may be Python) is never called from a worker; a cancel or a
// worker's exception stops the others and is rethrown here.
void forEachRow(const RenderSettings& settings, int rows, const char* stage, float progressFrom,
                float progressTo, const std::function<void(int)>& rowFn);

}  // namespace ss
