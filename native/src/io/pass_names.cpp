// How pass and channel names are built from, and split back into, light, method and layer.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/pass_names.h"

#include "core/method_names.h"
#include "core/names.h"

namespace ss {

std::string sanitizePassToken(const std::string& text) { return passToken(text); }

std::string passName(const std::string& light, const std::string& method, const std::string& layer) {
    std::string name = sanitizePassToken(light);
    name += '_';
    name += sanitizePassToken(method);
    if (layer != "V") {
        name += '_';
        name += sanitizePassToken(layer);
    }
    return name;
}

std::string channelName(const std::string& viewLayer, const std::string& pass) {
    return viewLayer + "." + pass + ".V";
}

bool splitPassName(const std::string& pass, PassParts* out) {
    size_t bestPos = std::string::npos;
    std::string bestMethod;
    // "auto" names the passes of a light rendered with auto whatever ran (ss_write_exr), so
    // `compare` can set them beside the reference.
    std::vector<std::string> methods = methodNames();
    methods.push_back("auto");
    for (const std::string& m : methods) {
        std::string token(1, '_');
        token += m;  // (not "_" + m: GCC 12 warns falsely on it, -Wrestrict)
        // Right-most occurrence that ends the name or is followed by "_<layer>".
        for (size_t pos = pass.rfind(token); pos != std::string::npos && pos > 0;
             pos = pos == 0 ? std::string::npos : pass.rfind(token, pos - 1)) {
            size_t end = pos + token.size();
            if (end == pass.size() || (pass[end] == '_' && end + 1 < pass.size())) {
                // Prefer the right-most match; at equal position the longer method name.
                if (bestPos == std::string::npos || pos > bestPos ||
                    (pos == bestPos && m.size() > bestMethod.size())) {
                    bestPos = pos;
                    bestMethod = m;
                }
                break;
            }
        }
    }
    if (bestPos == std::string::npos) return false;
    out->light = pass.substr(0, bestPos);
    out->method = bestMethod;
    size_t end = bestPos + 1 + bestMethod.size();
    out->layer = end == pass.size() ? "V" : pass.substr(end + 1);
    return true;
}

}  // namespace ss
