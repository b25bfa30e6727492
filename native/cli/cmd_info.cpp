// What `softshadow info` prints: the GL backend the library got, its renderer and limits.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli_common.h"

namespace ss::cli {

int runInfo(const std::vector<std::string>& argv) {
    Args args(argv, {"--backend"}, {"--json"});
    if (!args.positional().empty()) throw CliError("info takes no file arguments");
    ss_context* raw = nullptr;
    check(ss_context_create(parseBackend(args.value("--backend", "auto")), &raw));
    std::unique_ptr<ss_context, void (*)(ss_context*)> context(raw, ss_context_destroy);
    std::vector<char> buffer(1 << 16);
    check(ss_context_info(context.get(), buffer.data(), buffer.size()));
    std::string text(buffer.data());
    if (args.flag("--json")) {
        std::printf("%s\n", text.c_str());
        return 0;
    }
    nlohmann::json info = nlohmann::json::parse(text, nullptr, false);
    if (info.is_discarded() || !info.is_object()) {
        std::printf("%s\n", text.c_str());
        return 0;
    }
    std::printf("softshadow %s\n", ss_version());
    for (const char* key : {"backend", "renderer", "vendor", "version"})
        if (info.contains(key))
            std::printf("%-10s %s\n", key, info[key].is_string() ? info[key].get<std::string>().c_str()
                                                                   : info[key].dump().c_str());
    for (auto it = info.begin(); it != info.end(); ++it) {
        std::string k = it.key();
        if (k == "backend" || k == "renderer" || k == "vendor" || k == "version") continue;
        if (it->is_object()) {
            std::printf("%s:\n", k.c_str());
            for (auto jt = it->begin(); jt != it->end(); ++jt)
                std::printf("  %-32s %s\n", jt.key().c_str(), jt->dump().c_str());
        } else {
            std::printf("%-10s %s\n", k.c_str(), it->dump().c_str());
        }
    }
    return 0;
}

}  // namespace ss::cli
