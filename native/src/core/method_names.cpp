// Which shadow methods the library has: the one list every other list is read from.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/method_names.h"

namespace ss {

const std::vector<std::string>& methodNames() {
    static const std::vector<std::string> names = {
        "shadow_map", "pcss", "dbuffer", "sweep", "penumbra_map", "occlusion_textures", "reference",
    };
    return names;
}

bool isMethodName(const std::string& name) {
    for (const std::string& n : methodNames())
        if (n == name) return true;
    return false;
}

}  // namespace ss
