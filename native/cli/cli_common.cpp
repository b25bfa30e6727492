// How the CLI parses its arguments and turns C API failures into messages.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "cli_common.h"

#include <cstdlib>

namespace ss::cli {

void check(ss_status status) {
    if (status != SS_OK) throw CliError(ss_last_error());
}

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valueOptions,
           const std::set<std::string>& flagOptions) {
    for (size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.size() < 2 || a[0] != '-' || a == "--") {
            positional_.push_back(a);
            continue;
        }
        std::string name = a, inlineValue;
        bool hasInline = false;
        if (size_t eq = a.find('='); a.rfind("--", 0) == 0 && eq != std::string::npos) {
            name = a.substr(0, eq);
            inlineValue = a.substr(eq + 1);
            hasInline = true;
        }
        if (flagOptions.count(name)) {
            if (hasInline) throw CliError("option " + name + " takes no value");
            flags_.insert(name);
        } else if (valueOptions.count(name)) {
            if (!hasInline && i + 1 >= argv.size()) throw CliError("option " + name + " needs a value");
            values_[name].push_back(hasInline ? inlineValue : argv[++i]);
        } else {
            throw CliError("unknown option '" + a + "'");
        }
    }
}

std::string Args::value(const std::string& name, const std::string& fallback) const {
    auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    if (it->second.size() > 1)
        throw CliError("option " + name + " is given " + std::to_string(it->second.size()) +
                       " times ('" + it->second[0] + "', '" + it->second[1] + "'); it takes one value");
    return it->second.back();
}

const std::vector<std::string>& Args::values(const std::string& name) const {
    static const std::vector<std::string> none;
    auto it = values_.find(name);
    return it == values_.end() ? none : it->second;
}

int Args::integer(const std::string& name, int fallback, int lo, int hi) const {
    if (!has(name)) return fallback;
    std::string v = value(name);
    char* end = nullptr;
    long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || n < lo || n > hi)
        throw CliError("option " + name + " needs a whole number in [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + "], got '" + v + "'");
    return int(n);
}

std::vector<std::string> splitList(const std::string& text, char separator) {
    std::vector<std::string> out;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find(separator, start);
        if (end == std::string::npos) end = text.size();
        if (end > start) out.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

ss_backend parseBackend(const std::string& name) {
    if (name == "auto") return SS_BACKEND_AUTO;
    if (name == "egl") return SS_BACKEND_EGL;
    if (name == "osmesa") return SS_BACKEND_OSMESA;
    throw CliError("unknown backend '" + name + "' (expected egl, osmesa or auto)");
}

std::string passName(const char* light, const char* method, const char* layer) {
    char name[1024];
    check(ss_pass_name(light, method, layer, name, sizeof name));
    return name;
}

}  // namespace ss::cli
