// How a light's light and shadow linking is read from and written to a scene file.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <nlohmann/json.hpp>

#include "core/scene.h"
#include "io/json_node.h"

namespace ss {

// Sets the links of every light of the file's `lights` array on `scene`, once its meshes are in:
// each of "receivers" and "blockers" is an array of meshes, by index into `meshes` or by name (a
// name must belong to exactly one mesh); a light without the key has no set (every mesh).
void readLightLinks(const JsonNode& lights, Scene& scene);

// Adds the light's sets to its JSON object as mesh indices (nothing for a light without).
void writeLightLinks(const Light& light, nlohmann::json& object);

}  // namespace ss
