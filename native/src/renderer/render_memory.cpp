// How a render's memory budget is worked out from its size and compared with the limit.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "renderer/render_memory.h"

#include <cstdio>

#include "core/error.h"
#include "core/memory_budget.h"
#include "scene_cache/scene_cache.h"
#include "renderer/refinement.h"

namespace ss {

void checkRenderMemory(const Scene& scene, int lightIndex, const std::string& method, RenderSettings& settings) {
    const int limitMib = settings.integer(kMemoryLimitSetting);
    settings.options.erase(kMemoryLimitSetting.key);
    const double limit = limitMib > 0 ? double(limitMib) * double(1 << 20) : physicalMemoryBytes();
    if (!(limit > 0.0)) return;
    const BudgetKind kind = method == "reference"                                     ? BudgetKind::Cpu
                            : method == "auto" || refinementRequested(settings) ? BudgetKind::Auto
                                                                                : BudgetKind::Gl;
    const Camera& camera = scene.camera();
    const int64_t pixels = int64_t(camera.width) * camera.height;
    int64_t triangles = 0;
    for (const Mesh& m : scene.meshes()) triangles += int64_t(m.triangles.size());
    const int mapSize = shadowMapSizeSetting(settings);
    const double need = renderPeakBytes(kind, pixels, triangles, mapSize > 0 ? mapSize : SceneCache::kDefaultShadowMapSize);
    if (need <= limit) return;
    const double perPixel = kind == BudgetKind::Auto ? kBudgetBytesPerPixelAuto
                            : kind == BudgetKind::Gl ? kBudgetBytesPerPixelGl
                                                     : kBudgetBytesPerPixelCpu;
    char text[512];
    std::snprintf(text, sizeof text,
                  "%s at %d x %d needs about %s (%s + %.0f bytes a pixel + %.0f bytes a triangle of the %lld), "
                  "more than the memory limit %s (%s): render at a lower resolution",
                  method.c_str(), camera.width, camera.height, bytesText(need).c_str(),
                  bytesText(kBudgetFixedBytes).c_str(), perPixel, kBudgetBytesPerTriangle, (long long)triangles,
                  bytesText(limit).c_str(),
                  limitMib > 0 ? "the setting memory_limit_mb" : "the machine's memory; memory_limit_mb sets another");
    fail(SS_ERROR_INVALID_ARGUMENT, "light '" + scene.light(lightIndex).name + "': " + text);
}

}  // namespace ss
