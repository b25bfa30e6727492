// How a scene is read from and written to the softshadow scene file (JSON, docs/scene-format.md),
// the format the Blender add-on exports and the CLI reads.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/memory_budget.h"
#include "core/scene.h"

namespace ss {

inline constexpr int kSceneFormatVersion = 1;

// Limits checked before anything is allocated (docs/scene-format.md, "Limits").
inline constexpr uint64_t kMaxSceneFileBytes = 256ull << 20;  // the JSON text
inline constexpr uint64_t kMaxMeshFileBytes = 2ull << 30;     // one positions_file / triangles_file
inline constexpr size_t kMaxLights = 10000;
inline constexpr size_t kMaxMeshes = 100000;

// Throws ss::Error naming the file, the JSON path (e.g. meshes[2].positions[7]) and the
// problem: SS_ERROR_IO for a missing/malformed file or a wrong value, SS_ERROR_INVALID_SCENE for
// what the scene model rejects (index out of range, zero-size light...).
Scene loadSceneFile(const std::string& path);

// The same from text; `baseDir` resolves external mesh files, `shownName` is used in messages.
// `maxGeometry` bounds the triangles and the vertices of all meshes together (each, checked
// before allocating); the fuzzer passes a smaller one so that every accepted input stays fast.
Scene parseSceneText(const std::string& text, const std::string& baseDir, const std::string& shownName,
                     int64_t maxGeometry = kMaxSceneTriangles);

// Writes the scene (lights and camera as matrices) atomically. Meshes with more than
// `inlineVertexLimit` vertices go to raw little-endian files next to it
// ("<stem>.<mesh index>.positions.f32" / ".triangles.u32"), the others inline.
void saveSceneFile(const Scene& scene, const std::string& path, size_t inlineVertexLimit = 65536);

}  // namespace ss
