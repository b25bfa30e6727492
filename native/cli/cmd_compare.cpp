// What `softshadow compare` prints: RMSE, mean and p99 absolute error, umbra and lit IoU for each
// pass two EXR files share (or each method against a reference method inside one file).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cstdio>
#include <set>

#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "io/exr_file.h"
#include "io/metrics.h"
#include "io/pass_names.h"

namespace ss::cli {

namespace {

struct Pair {
    const ExrPass* a;
    const ExrPass* b;
};

bool isMaskPass(const ExrPass& p) {
    PassParts parts;
    return splitPassName(p.pass, &parts) && parts.layer == "mask";
}

// The mask that belongs to a pass: "<light>_<method>_mask" in the same file.
const ExrPass* ownMask(const ExrContents& file, const ExrPass& p) {
    PassParts parts;
    if (!splitPassName(p.pass, &parts)) return nullptr;
    return file.find(passName(parts.light, parts.method, "mask"));
}

std::vector<Pair> pairSameNames(const ExrContents& a, const ExrContents& b) {
    std::vector<Pair> out;
    for (const ExrPass& p : a.passes)
        if (!isMaskPass(p))
            if (const ExrPass* q = b.find(p.pass)) out.push_back({&p, q});
    return out;
}

// Same light and layer, different methods (e.g. reference.exr against shadow_map.exr).
std::vector<Pair> pairAcrossMethods(const ExrContents& a, const ExrContents& b, bool sameFile,
                                    const std::string& against) {
    std::vector<Pair> out;
    for (const ExrPass& p : a.passes) {
        PassParts pp;
        // Across methods only the visibility passes are comparable: the other layers
        // (masks, debug distances) mean different things per method.
        if (!splitPassName(p.pass, &pp) || pp.layer != "V") continue;
        if (sameFile && pp.method != against) continue;
        for (const ExrPass& q : b.passes) {
            PassParts qp;
            if (!splitPassName(q.pass, &qp) || qp.method == pp.method) continue;
            if (qp.light == pp.light && qp.layer == pp.layer) out.push_back({&p, &q});
        }
    }
    return out;
}

}  // namespace

int runCompare(const std::vector<std::string>& argv) {
    Args args(argv, {"--mask", "--against"}, {"--json"});
    const auto& files = args.positional();
    if (files.empty() || files.size() > 2) throw CliError("compare needs one or two EXR files");
    ExrContents a = readMultilayerExr(files[0]);
    ExrContents b = files.size() == 2 ? readMultilayerExr(files[1]) : ExrContents{};
    bool sameFile = files.size() == 1;
    const ExrContents& fb = sameFile ? a : b;
    std::string against = args.value("--against", "reference");

    std::vector<Pair> pairs;
    if (!sameFile) pairs = pairSameNames(a, b);
    if (pairs.empty()) pairs = pairAcrossMethods(a, fb, sameFile, against);
    if (pairs.empty())
        throw CliError(sameFile ? "'" + files[0] + "' has no pass of another method to compare with its '" +
                                      against + "' passes"
                                : "'" + files[0] + "' and '" + files[1] + "' share no pass");

    std::string maskOption = args.value("--mask");
    const ExrPass* fixedMask = nullptr;
    if (!maskOption.empty() && maskOption != "none") {
        fixedMask = a.find(maskOption);
        if (!fixedMask) fixedMask = fb.find(maskOption);
        if (!fixedMask) throw CliError("no pass named '" + maskOption + "' to use as the mask");
    }

    nlohmann::json rows = nlohmann::json::array();
    for (const Pair& pair : pairs) {
        Image mask;
        const Image* maskPtr = nullptr;
        std::string maskName = "all pixels";
        if (fixedMask) {
            maskPtr = &fixedMask->image;
            maskName = fixedMask->pass;
        } else if (maskOption.empty()) {
            // Pixels both methods call surfaces the light reaches.
            const ExrPass* ma = ownMask(a, *pair.a);
            const ExrPass* mb = ownMask(fb, *pair.b);
            if (ma && mb) {
                mask = ma->image;
                for (size_t i = 0; i < mask.pixels.size() && i < mb->image.pixels.size(); ++i)
                    mask.pixels[i] = (ma->image.pixels[i] > 0.5f && mb->image.pixels[i] > 0.5f) ? 1.0f : 0.0f;
                maskPtr = &mask;
                maskName = ma == mb ? ma->pass : ma->pass + " & " + mb->pass;
            } else if (ma || mb) {
                maskPtr = &(ma ? ma : mb)->image;
                maskName = (ma ? ma : mb)->pass;
            }
        }
        Metrics m;
        try {
            m = compareVisibility(pair.a->image, pair.b->image, maskPtr);
        } catch (const std::exception& e) {
            throw CliError("comparing '" + pair.a->pass + "' with '" + pair.b->pass + "': " + e.what());
        }
        // A score over no pixel would read as a perfect match.
        if (m.pixels == 0)
            throw CliError("comparing '" + pair.a->pass + "' with '" + pair.b->pass + "': mask '" + maskName +
                           "' selects no pixel (compared: mask values > 0.5; NaN is outside), nothing to compare");
        nlohmann::json row = nlohmann::json::parse(m.toJson());
        row["a"] = pair.a->pass;
        row["b"] = pair.b->pass;
        row["mask"] = maskName;
        rows.push_back(row);
    }

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
