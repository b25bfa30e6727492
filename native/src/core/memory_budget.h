// What a render and a scene take in memory at their peak, as measured (docs/reliability.md,
// "Memory budget"), and the limit a render or a scene file must fit in.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <string>

#include "core/settings.h"

namespace ss {

// Measured with /usr/bin/time -v on `softshadow render` (bench/memory_budget.sh: one light,
// llvmpipe, 1024² to 8192²): the program, GL and Embree state (auto holds both: 236 to 260 MB
// beside its per-pixel share and its map, the most at 1024²; shadow_map alone about 115 MB). The
// render's own shadow map is counted apart (renderPeakBytes); several lights in one process add
// up to SceneCache::kDefaultShadowMapBudget (256 MiB) of cached maps.
inline constexpr double kBudgetFixedBytes = 280e6;
// A pixel of the camera for a GL method: the camera pass (two RGBA32F targets, an RG32F one and
// depth: 44 bytes), the method's targets and the result's float layers. Measured (4096² to
// 8192²): shadow_map 78, pcss and penumbra_map about 80, dbuffer 116, occlusion_textures 133.
inline constexpr double kBudgetBytesPerPixelGl = 140.0;
// auto (its candidates one at a time, only results that can still win kept) and refinement (its
// per-pixel images beside the method's). Measured: auto refined 146 (4096² to 8192²).
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
// The sweep's shadow mesh (ss_sweep_shadow_mesh, and the sweep method's render), by its
// triangles: the fill's trapezoids and mesh and the C API's shared-corner copy (measured 245 to
// 343 bytes a triangle, 64 to 256 samples on a torus), and with irradiance weights (the default)
// each triangle's weights per sample and for all of them, doubles for 3 of 4 triangles (6
// bytes a triangle per sample + 1; measured 1.58 GB for 879k triangles from 256 samples).
inline constexpr double kBudgetBytesPerSweepTriangle = 400.0;
inline constexpr double kBudgetBytesPerSweepWeight = 6.0;

enum class BudgetKind { Gl, Auto, Cpu };
double renderPeakBytes(BudgetKind kind, int64_t pixels, int64_t triangles, int shadowMapSize);
double sweepMeshPeakBytes(int64_t triangles, int samples, bool irradianceWeights);

// The one budget comparison: throws ss::Error(SS_ERROR_INVALID_ARGUMENT) "WHAT needs about NEED
// (HOW), more than the memory limit LIMIT (where it comes from): ADVICE" when need is over it.
void requireWithinMemory(const MemoryLimit& limit, double need, const std::string& what, const std::string& how,
                         const std::string& advice);
// The machine's physical memory (sysconf), or 0 where it cannot be told.
double physicalMemoryBytes();
// "9.13 GB"
std::string bytesText(double bytes);

}  // namespace ss
