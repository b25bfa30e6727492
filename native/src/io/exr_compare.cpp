// How one or two visibility EXRs are paired pass by pass and compared (ss_compare_exr).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/exr_compare.h"

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/exr_file.h"
#include "io/metrics.h"
#include "io/pass_names.h"

namespace ss {

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

std::string compareExrFiles(const std::string& pathA, const std::string& pathB, const std::string& against,
                            const std::string& maskPass) {
    ExrContents a = readMultilayerExr(pathA);
    const bool sameFile = pathB.empty();
    ExrContents b = sameFile ? ExrContents{} : readMultilayerExr(pathB);
    const ExrContents& fb = sameFile ? a : b;

    std::vector<Pair> pairs;
    if (!sameFile) pairs = pairSameNames(a, b);
    if (pairs.empty()) pairs = pairAcrossMethods(a, fb, sameFile, against);
    if (pairs.empty())
        fail(SS_ERROR_INVALID_ARGUMENT,
             sameFile ? "'" + pathA + "' has no pass of another method to compare with its '" + against + "' passes"
                      : "'" + pathA + "' and '" + pathB + "' share no pass");

    const ExrPass* fixedMask = nullptr;
    if (!maskPass.empty() && maskPass != "none") {
        fixedMask = a.find(maskPass);
        if (!fixedMask) fixedMask = fb.find(maskPass);
        if (!fixedMask) fail(SS_ERROR_INVALID_ARGUMENT, "no pass named '" + maskPass + "' to use as the mask");
    }

    nlohmann::json rows = nlohmann::json::array();
    for (const Pair& pair : pairs) {
        Image mask;
        const Image* maskPtr = nullptr;
        std::string maskName = "all pixels";
        if (fixedMask) {
            maskPtr = &fixedMask->image;
            maskName = fixedMask->pass;
        } else if (maskPass.empty()) {
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
            fail(SS_ERROR_INVALID_ARGUMENT, "comparing '" + pair.a->pass + "' with '" + pair.b->pass + "': " + e.what());
        }
        // A score over no pixel would read as a perfect match.
        if (m.pixels == 0)
            fail(SS_ERROR_INVALID_ARGUMENT, "comparing '" + pair.a->pass + "' with '" + pair.b->pass + "': mask '" +
                                                maskName + "' selects no pixel (compared: mask values > 0.5; NaN is "
                                                "outside), nothing to compare");
        nlohmann::json row = nlohmann::json::parse(m.toJson());
        row["a"] = pair.a->pass;
        row["b"] = pair.b->pass;
        row["mask"] = maskName;
        rows.push_back(row);
    }

    return rows.dump();
}

}  // namespace ss
