// Which methods exist (the contract names) and the factory that makes one by name.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/error.h"
#include "methods/method.h"

namespace ss {

// One factory per method, defined in that method's own file.
std::unique_ptr<Method> makeShadowMapMethod();
std::unique_ptr<Method> makeReferenceMethod();
std::unique_ptr<Method> makeSweepMethod();
std::unique_ptr<Method> makePcssMethod();
std::unique_ptr<Method> makePenumbraMapMethod();
std::unique_ptr<Method> makeOcclusionTexturesMethod();
std::unique_ptr<Method> makeDbufferMethod();

namespace {
struct Entry {
    const char* name;
    std::unique_ptr<Method> (*make)();
};
const std::vector<Entry>& entries() {
    static const std::vector<Entry> table = {
        {"shadow_map", makeShadowMapMethod},
        {"pcss", makePcssMethod},
        {"dbuffer", makeDbufferMethod},
        {"sweep", makeSweepMethod},
        {"penumbra_map", makePenumbraMapMethod},
        {"occlusion_textures", makeOcclusionTexturesMethod},
        {"reference", makeReferenceMethod},
    };
    return table;
}
}  // namespace

std::unique_ptr<Method> createMethod(const std::string& name) {
    for (const Entry& e : entries())
        if (name == e.name) return e.make();
    std::string known;
    for (const Entry& e : entries()) known += std::string(known.empty() ? "" : ", ") + e.name;
    fail(SS_ERROR_INVALID_ARGUMENT, "unknown method '" + name + "' (known: " + known + ", auto)");
}

}  // namespace ss
