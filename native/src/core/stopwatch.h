// How long a stage took, in milliseconds (the stage timings the benchmark reports).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <chrono>

namespace ss {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace ss
