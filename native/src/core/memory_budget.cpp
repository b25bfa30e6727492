// How the memory budget adds up, and how much memory the machine has.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/memory_budget.h"

#include <unistd.h>

#include <cstdio>

#include "core/error.h"

namespace ss {

double renderPeakBytes(BudgetKind kind, int64_t pixels, int64_t triangles, int shadowMapSize) {
    const double perPixel = kind == BudgetKind::Auto ? kBudgetBytesPerPixelAuto
                            : kind == BudgetKind::Gl ? kBudgetBytesPerPixelGl
                                                     : kBudgetBytesPerPixelCpu;
    // The render's own map beside the cached ones (distance + depth, 4 bytes each).
    const double map = kind == BudgetKind::Cpu ? 0.0 : 8.0 * double(shadowMapSize) * double(shadowMapSize);
    return kBudgetFixedBytes + perPixel * double(pixels) + kBudgetBytesPerTriangle * double(triangles) + map;
}

double sweepMeshPeakBytes(int64_t triangles, int samples, bool irradianceWeights) {
    const double perTriangle =
        kBudgetBytesPerSweepTriangle + (irradianceWeights ? kBudgetBytesPerSweepWeight * (double(samples) + 1.0) : 0.0);
    return perTriangle * double(triangles);
}

void requireWithinMemory(const MemoryLimit& limit, double need, const std::string& what, const std::string& how,
                         const std::string& advice) {
    if (!(limit.bytes > 0.0) || need <= limit.bytes) return;
    fail(SS_ERROR_INVALID_ARGUMENT,
         what + " needs about " + bytesText(need) + " (" + how + "), more than the memory limit " + bytesText(limit.bytes) +
             " (" + (limit.fromSetting ? "the setting memory_limit_mb" : "the machine's memory; memory_limit_mb sets another") +
             "): " + advice);
}

double physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && size > 0 ? double(pages) * double(size) : 0.0;
}

std::string bytesText(double bytes) {
    char text[32];
    if (bytes >= 1e9) std::snprintf(text, sizeof text, "%.2f GB", bytes / 1e9);
    else std::snprintf(text, sizeof text, "%.0f MB", bytes / 1e6);
    return text;
}

}  // namespace ss
