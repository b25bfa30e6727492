// How a render's memory budget is worked out from its size and compared with the limit.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "renderer/render_memory.h"

#include <cstdio>

#include "core/memory_budget.h"
#include "scene_cache/scene_cache.h"

namespace ss {

MemoryLimit takeMemoryLimit(RenderSettings& settings) {
    const int limitMib = settings.integer(kMemoryLimitSetting);
    settings.options.erase(kMemoryLimitSetting.key);
    MemoryLimit limit;
    limit.fromSetting = limitMib > 0;
    limit.bytes = limitMib > 0 ? double(limitMib) * double(1 << 20) : physicalMemoryBytes();
    settings.memoryLimit = limit;
    return limit;
}

void checkRenderMemory(const Scene& scene, int lightIndex, const std::string& method, RenderSettings& settings) {
    const MemoryLimit limit = takeMemoryLimit(settings);
    const BudgetKind kind = method == "reference"                                     ? BudgetKind::Cpu
                            : method == "auto" || settings.refine ? BudgetKind::Auto
                                                                                : BudgetKind::Gl;
    const Camera& camera = scene.camera();
    const int64_t pixels = int64_t(camera.width) * camera.height;
    int64_t triangles = 0;
    for (const Mesh& m : scene.meshes()) triangles += int64_t(m.triangles.size());
    const int mapSize = shadowMapSizeSetting(settings);
    const double need = renderPeakBytes(kind, pixels, triangles, mapSize > 0 ? mapSize : SceneCache::kDefaultShadowMapSize);
    const double perPixel = kind == BudgetKind::Auto ? kBudgetBytesPerPixelAuto
                            : kind == BudgetKind::Gl ? kBudgetBytesPerPixelGl
                                                     : kBudgetBytesPerPixelCpu;
    char what[256], how[256];
    std::snprintf(what, sizeof what, "light '%s': %s at %d x %d", scene.light(lightIndex).name.c_str(), method.c_str(),
                  camera.width, camera.height);
    std::snprintf(how, sizeof how, "%s + %.0f bytes a pixel + %.0f bytes a triangle of the %lld",
                  bytesText(kBudgetFixedBytes).c_str(), perPixel, kBudgetBytesPerTriangle, (long long)triangles);
    requireWithinMemory(limit, need, what, how, "render at a lower resolution");
}

}  // namespace ss
