// What a render and a scene take in memory at their peak, as measured (docs/reliability.md,
// "Memory budget"), and the limit a render or a scene file must fit in.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <string>

namespace ss {

// Measured with /usr/bin/time -v on `softshadow render` (bench/memory_budget.sh: one light,
// llvmpipe, 1024² to 8192²): the program, GL and Embree state and one 2048² shadow map. Several
// lights in one process add up to SceneCache::kDefaultShadowMapBudget (256 MiB) of cached maps.
inline constexpr double kBudgetFixedBytes = 250e6;
// A pixel of the camera for a GL method: the camera pass (two RGBA32F targets, an RG32F one and
// depth: 44 bytes), the method's targets and the result's float layers. Measured: shadow_map 78,
// dbuffer 118.
inline constexpr double kBudgetBytesPerPixelGl = 120.0;
// auto (its candidates one at a time, only results that can still win kept) and refine=on (its
// per-pixel images beside the method's). Measured: auto with refine=on 139.
inline constexpr double kBudgetBytesPerPixelAuto = 150.0;
// The reference: its float images, no GL. Measured: 17 at 1024².
inline constexpr double kBudgetBytesPerPixelCpu = 24.0;
// A triangle of the scene (a vertex for two triangles counted in): object-space and world
// positions and face normals, indices, edge adjacency, then GPU buffers (shadow_map: 399
// measured) or the Embree BVH (reference: 456 measured; a 2M-triangle sphere, 64² pixels).
inline constexpr double kBudgetBytesPerTriangle = 460.0;
// What a scene file may build in all (primitives, inline and external meshes), triangles and
// vertices each, checked before anything is allocated for it (16.8M: about 7.7 GB by
// kBudgetBytesPerTriangle).
inline constexpr int64_t kMaxSceneTriangles = int64_t(1) << 24;

enum class BudgetKind { Gl, Auto, Cpu };
double renderPeakBytes(BudgetKind kind, int64_t pixels, int64_t triangles, int shadowMapSize);
// The machine's physical memory (sysconf), or 0 where it cannot be told.
double physicalMemoryBytes();
// "9.13 GB"
std::string bytesText(double bytes);

}  // namespace ss
