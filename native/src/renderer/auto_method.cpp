// How `auto` chooses per light: its candidates and prior, the trial loop over the sparse check,
// and the shape rule where no check can be made.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "renderer/auto_method.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "core/error.h"
#include "methods/sweep/receiver.h"

namespace ss {

namespace {

constexpr SettingSpec kCheckPixels = [] {
    SettingSpec s = intSetting("check_pixels", 0, 0, 1 << 24,
                               "pixels the sparse check traces (0: no check, choose by the light's shape)");
    s.renderDefault = "1 in 16 pixels, 4096..65536";
    return s;
}();
constexpr SettingSpec kCheckSamples =
    intSetting("check_samples", 0, 0, 1 << 16, "light samples per sparse-check pixel (0: the check's default)");

// Two estimates this close are a tie, and the cheaper candidate wins: the check's own sampling
// error is about this large at a few thousand pixels.
bool clearlyBetter(double a, double b) { return a < b * 0.97 - 0.0005; }

}  // namespace

namespace {
// Every method but the reference, the truth itself (not an interactive method), may be a candidate.
bool autoMayTry(const std::string& method) { return method != "reference"; }
}  // namespace

const SettingTable& autoSettingTable() {
    static const SettingTable table = [] {
        SettingTable t{kCheckPixels, kCheckSamples};
        for (const std::string& name : methodNames())
            if (autoMayTry(name)) t = composed(std::move(t), createMethod(name)->settingTable());
        return t;
    }();
    return table;
}

RenderSettings candidateSettings(const RenderSettings& settings, const SettingTable& candidate) {
    RenderSettings own = settings;
    own.options.clear();
    for (const auto& [key, value] : settings.options)
        if (findSetting(candidate, key)) own.options.emplace(key, value);
    return own;
}

AutoCheckSize autoCheckSize(const RenderSettings& settings, const Camera& camera) {
    return {settings.integer(kCheckPixels, sparseCheckDefaultPixels(camera.width, camera.height)),
            settings.integer(kCheckSamples)};
}

namespace {
// Whether every point of the light lies on the same side of every face: then the mesh's only
// silhouette, seen from anywhere on the light, is its border.
bool facesOneSideOfLight(const Mesh& mesh, const Light& light) {
    const glm::dvec3 centre(light.position());
    const double reach = light.type == LightType::Point || light.type == LightType::Spot
                             ? double(light.radius)
                             : std::sqrt(double(glm::dot(light.halfAxisX(), light.halfAxisX())) +
                                         double(glm::dot(light.halfAxisY(), light.halfAxisY())));
    const glm::dvec3 toSun = -glm::dvec3(light.direction());
    const double sunSlack = std::sin(double(light.sunHalfAngle()));
    int side = 0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double length = glm::length(n);
        if (!(length > 0.0)) continue;  // a degenerate face has no side
        const double distance = light.type == LightType::Sun ? glm::dot(n, toSun) : glm::dot(n, centre - a);
        const double slack = length * (light.type == LightType::Sun ? sunSlack : reach);
        const int faceSide = distance > slack ? 1 : distance < -slack ? -1 : 0;
        if (faceSide == 0 || (side != 0 && faceSide != side)) return false;
        side = faceSide;
    }
    return true;
}

// An open caster whose faces all see the light from one side (a floor, a wall, a curved ground
// or backdrop: Blender lets every object cast by default) is not a problem for the volumes:
// its only silhouette is its border, whose volumes point away from the light, behind it. Any
// other open or non-manifold caster is.
bool castersClosedForVolumes(const Scene& scene, int lightIndex) {
    const Light& light = scene.light(lightIndex);
    for (size_t i = 0; i < scene.meshes().size(); ++i) {
        const Mesh& m = scene.meshes()[i];
        if (scene.castsFor(int(i), lightIndex) && !m.report.closedManifold() && !isPlanarMesh(m) &&
            !facesOneSideOfLight(m, light))
            return false;
    }
    return true;
}
}  // namespace

std::vector<std::string> autoCandidates(const Scene& scene, int lightIndex) {
    const bool closed = castersClosedForVolumes(scene, lightIndex);
    std::vector<std::string> out;
    for (const std::string& name : methodNames()) {
        if (!autoMayTry(name)) continue;
        // dbuffer's volumes assume closed 2-manifold casters (docs/methods/dbuffer.md).
        if (name == "dbuffer" && !closed) continue;
        out.push_back(name);
    }
    return out;
}

bool autoPriorKeeps(const Scene& scene, int lightIndex, const std::string& method) {
    const LightType type = scene.light(lightIndex).type;
    const bool rectangular = type == LightType::Square || type == LightType::Rectangle;
    const bool round = type == LightType::Disk || type == LightType::Ellipse || type == LightType::Point ||
                       type == LightType::Spot;
    if (method == "dbuffer") return round;
    if (method == "occlusion_textures") return rectangular;
    return true;
}

std::string chooseAutoMethodByShape(const Scene& scene, int lightIndex) {
    // Used only where the sparse check cannot run (docs/methods/README.md): each light gets the
    // method whose paper models its shape, unless the scene breaks that method's assumptions.
    const Light& light = scene.light(lightIndex);
    const bool castersClosed = castersClosedForVolumes(scene, lightIndex);
    switch (light.type) {
        case LightType::Square:
        case LightType::Rectangle:
            // Occlusion textures are built for rectangular lights and need no closed meshes.
            return "occlusion_textures";
        case LightType::Disk:
        case LightType::Ellipse:
        case LightType::Point:
        case LightType::Spot:
            // Umbra/penumbra volumes give correct boundaries for disks, but their extrusion
            // assumes closed 2-manifold casters; PCSS accepts any triangle soup.
            return castersClosed ? "dbuffer" : "pcss";
        case LightType::Sun: return "pcss";
    }
    return "pcss";
}

AutoChoice chooseAutoMethod(const Scene& scene, int lightIndex, const RenderSettings& settings,
                            const SparseCheck* check, const AutoMethods& methods, AutoTrials& trials) {
    auto settingsOf = [&](const std::string& candidate) {
        return candidateSettings(settings, methods.method(candidate).settingTable());
    };
    AutoChoice choice;
    if (!check) {
        choice.method = chooseAutoMethodByShape(scene, lightIndex);
        choice.layers = methods.render(choice.method, settingsOf(choice.method));
        trials.rendered.push_back(choice.method);
        return choice;
    }
    // The candidates the prior keeps render first; a method whose lower bound on the check is
    // above zero waits until the others set the score it must beat.
    const std::vector<std::string> candidates = autoCandidates(scene, lightIndex);
    std::vector<std::string> first, bounded;
    for (const std::string& candidate : candidates) {
        if (!autoPriorKeeps(scene, lightIndex, candidate))
            trials.skippedByPrior.push_back(candidate);
        else if (methods.method(candidate).errorLowerBound(*check, scene, lightIndex) > 0.0)
            bounded.push_back(candidate);
        else
            first.push_back(candidate);
    }
    std::map<std::string, std::pair<double, Layers>> scored;
    double best = std::numeric_limits<double>::infinity();
    auto attempt = [&](const std::string& candidate) {
        settings.report(0.0f, ("auto: trying " + candidate).c_str());
        Layers tried;
        try {
            tried = methods.render(candidate, settingsOf(candidate));
        } catch (const Error& e) {
            // A method that cannot take this scene is not a candidate here.
            if (e.status() == SS_ERROR_UNSUPPORTED) return;
            throw;
        }
        trials.rendered.push_back(candidate);
        const double e = estimatedRmse(*check, tried);
        if (!std::isfinite(e)) return;
        best = std::min(best, e);
        scored.emplace(candidate, std::make_pair(e, std::move(tried)));
        // A result the best so far is clearly better than can never be chosen (the choice below
        // only ever moves to a clearly better one): its layers go now, so auto holds about one
        // result, not one per candidate.
        for (auto& [other, score] : scored)
            if (clearlyBetter(best, score.first)) score.second = Layers();
    };
    for (const std::string& candidate : first) attempt(candidate);
    for (const std::string& candidate : bounded) {
        // It could still win: its score may be at the bound, and a cheaper candidate keeps a tie
        // (clearlyBetter).
        if (!std::isfinite(best) ||
            !clearlyBetter(best, methods.method(candidate).errorLowerBound(*check, scene, lightIndex)))
            attempt(candidate);
        else trials.skippedByBound.push_back(candidate);
    }
    // The choice over what rendered, in the candidates' order of cost: the lowest estimate, the
    // cheaper on a tie.
    double estimate = std::numeric_limits<double>::quiet_NaN();
    for (const std::string& candidate : candidates) {
        auto it = scored.find(candidate);
        if (it == scored.end()) continue;
        if (choice.method.empty() || clearlyBetter(it->second.first, estimate))
            choice.method = candidate, estimate = it->second.first;
    }
    if (choice.method.empty())
        fail(SS_ERROR_UNSUPPORTED,
             "auto: no method can render light '" + scene.light(lightIndex).name + "' in this scene");
    choice.layers = std::move(scored.at(choice.method).second);
    return choice;
}

}  // namespace ss
