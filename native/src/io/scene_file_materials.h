// How a mesh's materials (what shadow rays see through) are read from and written to a scene file.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <nlohmann/json.hpp>

#include "core/mesh_alpha.h"
#include "io/json_node.h"

namespace ss {

// The "materials" member of a mesh (docs/scene-format.md): throws ss::Error naming the JSON path
// for a malformed value; the scene model checks it against the mesh's triangles.
MeshAlpha readMeshAlpha(const JsonNode& n);
nlohmann::json meshAlphaJson(const MeshAlpha& alpha);

}  // namespace ss
