// How a light's linked mesh sets are checked, queried and renumbered.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/light_links.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace ss {

bool LightLinks::contains(const std::optional<std::vector<int>>& set, int mesh) {
    return !set || std::binary_search(set->begin(), set->end(), mesh);
}

void LightLinks::meshRemoved(int index) {
    for (std::optional<std::vector<int>>* set : {&receivers, &blockers}) {
        if (!*set) continue;
        std::vector<int> kept;
        for (int m : **set)
            if (m != index) kept.push_back(m > index ? m - 1 : m);
        **set = std::move(kept);
    }
}

std::vector<int> linkedMeshSet(std::vector<int> meshes, size_t meshCount, const char* what) {
    for (int m : meshes)
        if (m < 0 || size_t(m) >= meshCount)
            fail(SS_ERROR_INVALID_ARGUMENT, std::string("light links: ") + what + " mesh index " + std::to_string(m) +
                                                " is out of range (the scene has " + std::to_string(meshCount) +
                                                " meshes)");
    std::sort(meshes.begin(), meshes.end());
    meshes.erase(std::unique(meshes.begin(), meshes.end()), meshes.end());
    return meshes;
}

}  // namespace ss
