// What `softshadow compare` prints: RMSE, mean and p99 absolute error, umbra and lit IoU for each
// pass two EXR files share (or each method against a reference method inside one file).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cstdio>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_common.h"

namespace ss::cli {

int runCompare(const std::vector<std::string>& argv) {
    Args args(argv, {"--mask", "--against"}, {"--json"});
    const auto& files = args.positional();
    if (files.empty() || files.size() > 2) throw CliError("compare needs one or two EXR files");
    std::string against = args.value("--against", "reference");
    std::string mask = args.value("--mask");
    const char* second = files.size() == 2 ? files[1].c_str() : nullptr;
    // The rows' size is known only once compared: asked again with the size the library names.
    std::string json(64 * 1024, '\0');
    size_t length = 0;
    ss_status status = ss_compare_exr(files[0].c_str(), second, against.c_str(), mask.c_str(), json.data(),
                                      json.size(), &length);
    if (status != SS_OK && length > json.size()) {
        json.assign(length, '\0');
        status = ss_compare_exr(files[0].c_str(), second, against.c_str(), mask.c_str(), json.data(), json.size(),
                                &length);
    }
    check(status);
    json.resize(length > 0 ? length - 1 : 0);
    nlohmann::json rows = nlohmann::json::parse(json);

    if (args.flag("--json")) {
        std::printf("%s\n", rows.dump(2).c_str());
        return 0;
    }
    auto rowName = [](const nlohmann::json& r) {
        return r["a"] == r["b"] ? r["a"].get<std::string>()
                                : r["a"].get<std::string>() + " vs " + r["b"].get<std::string>();
    };
    int width = 13;
    for (const auto& r : rows) width = std::max(width, int(rowName(r).size()));
    std::printf("%-*s %9s %9s %9s %9s %9s %9s\n", width, "pass (A vs B)", "pixels", "rmse", "mean", "p99",
                "umbra_iou", "lit_iou");
    for (const auto& r : rows)
        std::printf("%-*s %9zu %9.5f %9.5f %9.5f %9.4f %9.4f\n", width, rowName(r).c_str(),
                    r["pixels"].get<size_t>(), r["rmse"].get<double>(), r["mean"].get<double>(),
                    r["p99"].get<double>(), r["umbra_iou"].get<double>(), r["lit_iou"].get<double>());
    std::set<std::string> masks;
    for (const auto& r : rows) masks.insert(r["mask"].get<std::string>());
    for (const std::string& m : masks) std::printf("mask: %s\n", m.c_str());
    return 0;
}

}  // namespace ss::cli
