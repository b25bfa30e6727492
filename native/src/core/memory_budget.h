// What a render and a scene take in memory at their peak, as measured (docs/reliability.md,
// "Memory budget"), and the limit a render or a scene file must fit in.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <string>

namespace ss {

// Measured with /usr/bin/time -v on `softshadow render` (bench/memory_budget.sh), llvmpipe:
// the program, GL and Embree state, and the cached shadow maps (256 MiB).
inline constexpr double kBudgetFixedBytes = 420e6;
// A pixel of the camera: the camera pass (three RGBA32F targets and depth, 52 bytes), the
// method's targets and read-backs and the result's float layers.
inline constexpr double kBudgetBytesPerPixelGl = 120.0;
// auto (its candidates one at a time, the best kept) and refine=on (its per-pixel images).
inline constexpr double kBudgetBytesPerPixelAuto = 180.0;
// The reference: its float images, no GL.
inline constexpr double kBudgetBytesPerPixelCpu = 40.0;
// A triangle of the scene (a vertex per triangle counted in): positions, indices, normals,
// edge adjacency, GPU buffers and the Embree BVH.
inline constexpr double kBudgetBytesPerTriangle = 400.0;
// What a scene file may build in all (primitives, inline and external meshes), checked before
// anything is allocated for it (16.8M: about 6.7 GB by kBudgetBytesPerTriangle).
inline constexpr int64_t kMaxSceneTriangles = int64_t(1) << 24;
inline constexpr int64_t kMaxSceneVertices = int64_t(1) << 24;

enum class BudgetKind { Gl, Auto, Cpu };
double renderPeakBytes(BudgetKind kind, int64_t pixels, int64_t triangles, int shadowMapSize);
// The machine's physical memory (sysconf), or 0 where it cannot be told.
double physicalMemoryBytes();
// "9.13 GB"
std::string bytesText(double bytes);

}  // namespace ss
