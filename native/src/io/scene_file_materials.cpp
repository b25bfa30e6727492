// How the "materials" member of a scene file's mesh maps to ss::MeshAlpha and back.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene_file_materials.h"

#include <string>

namespace ss {
namespace {

constexpr const char* kWrapNames[] = {"repeat", "extend", "clip"};
constexpr int64_t kMaxTexelsInFile = int64_t(1) << 24;

AlphaMaterial readMaterial(const JsonNode& n) {
    n.expectKeys({"alpha", "width", "height", "texels", "wrap", "interpolation", "name", "comment"});
    AlphaMaterial m;
    m.constant = n.real("alpha", 1.0f);
    if (n.has("wrap")) {
        const std::string w = n.at("wrap").string();
        int found = -1;
        for (int i = 0; i < 3; ++i)
            if (w == kWrapNames[i]) found = i;
        if (found < 0) n.at("wrap").fail("'" + w + "' is not repeat, extend or clip");
        m.wrap = AlphaWrap(found);
    }
    if (n.has("interpolation")) {
        const std::string f = n.at("interpolation").string();
        if (f != "linear" && f != "closest") n.at("interpolation").fail("'" + f + "' is not linear or closest");
        m.filter = f == "closest" ? AlphaFilter::Closest : AlphaFilter::Linear;
    }
    if (n.has("texels") || n.has("width") || n.has("height")) {
        m.width = int(n.at("width").integer(1, kMaxTexelsInFile));
        m.height = int(n.at("height").integer(1, kMaxTexelsInFile));
        JsonNode t = n.at("texels");
        if (int64_t(m.width) * m.height > kMaxTexelsInFile || t.size() != size_t(m.width) * size_t(m.height))
            t.fail("has " + std::to_string(t.size()) + " texels, not width x height (" + std::to_string(m.width) +
                   " x " + std::to_string(m.height) + ", at most 2^24)");
        m.texels = t.reals();
    }
    return m;
}

}  // namespace

MeshAlpha readMeshAlpha(const JsonNode& n) {
    n.expectKeys({"uvs", "triangle_material", "list", "comment"});
    MeshAlpha alpha;
    if (n.has("uvs")) {
        JsonNode u = n.at("uvs");
        std::vector<float> v = u.reals();
        if (v.size() % 2) u.fail("has " + std::to_string(v.size()) + " numbers, not a multiple of 2");
        alpha.cornerUvs.resize(v.size() / 2);
        for (size_t i = 0; i < alpha.cornerUvs.size(); ++i) alpha.cornerUvs[i] = glm::vec2(v[2 * i], v[2 * i + 1]);
    }
    if (n.has("triangle_material")) {
        JsonNode t = n.at("triangle_material");
        alpha.triangleMaterial.resize(t.size());
        for (size_t i = 0; i < alpha.triangleMaterial.size(); ++i)
            alpha.triangleMaterial[i] = uint32_t(t.at(i).integer(0, 0xfffffffe));
    }
    JsonNode list = n.at("list");
    for (size_t i = 0; i < list.size(); ++i) alpha.materials.push_back(readMaterial(list.at(i)));
    return alpha;
}

nlohmann::json meshAlphaJson(const MeshAlpha& alpha) {
    nlohmann::json j = nlohmann::json::object();
    if (!alpha.cornerUvs.empty()) {
        nlohmann::json u = nlohmann::json::array();
        for (const glm::vec2& uv : alpha.cornerUvs) u.push_back(uv.x), u.push_back(uv.y);
        j["uvs"] = std::move(u);
    }
    if (!alpha.triangleMaterial.empty()) j["triangle_material"] = alpha.triangleMaterial;
    nlohmann::json list = nlohmann::json::array();
    for (const AlphaMaterial& m : alpha.materials) {
        nlohmann::json e = {{"alpha", m.constant},
                            {"wrap", kWrapNames[int(m.wrap)]},
                            {"interpolation", m.filter == AlphaFilter::Closest ? "closest" : "linear"}};
        if (m.textured()) {
            e["width"] = m.width;
            e["height"] = m.height;
            e["texels"] = m.texels;
        }
        list.push_back(std::move(e));
    }
    j["list"] = std::move(list);
    return j;
}

}  // namespace ss
