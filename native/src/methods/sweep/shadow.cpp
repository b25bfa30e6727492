// How the sweep method's CPU stages run in order: samples, projection, per-sample sweep,
// merge and fill.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/shadow.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/stopwatch.h"
#include "methods/sweep/weights.h"
#include "planar/outline.h"
#include "planar/rings.h"
#include "sampling/light_samples.h"

namespace ss {


namespace {

constexpr SettingSpec kReceiver =
    textSetting("receiver", "name of the planar receiver mesh (default: the one the shadow falls on)");
constexpr SettingSpec kFill = choiceSetting("fill", "smooth|steps|rings", "how the penumbra between sample outlines is filled");
constexpr SettingSpec kBorder = floatSetting("border", 0.25, 0.0, 1.0, "share of the light samples on the light's border");
constexpr SettingSpec kClusters =
    intSetting("clusters", 1, 1, 64, "strips a square or rectangle light is split into, each swept on its own");
// How many sets of light samples are swept and averaged; auto: from the widest penumbra on
// screen (sweepPassesFor), at most kSweepMaxPasses.
constexpr SettingSpec kPasses = choiceSetting("passes", "auto|1|2|3|4|5|6|7|8|9|10|11|12|13|14|15|16",
                                              "sets of light samples swept and averaged (auto: by the penumbra's width on screen)");
constexpr SettingSpec kWeights =
    choiceSetting("weights", "irradiance|equal", "sample weights: by irradiance, or equal (the paper)");

}  // namespace

const SettingTable& sweepSettings() {
    static const SettingTable table{kReceiver, kFill, kBorder, kClusters, kPasses, kWeights, kSweepRaster};
    return table;
}

SweepOptions sweepOptions(const RenderSettings& settings) {
    SweepOptions o;
    if (settings.samples < 0) fail(SS_ERROR_INVALID_ARGUMENT, "sweep: samples must not be negative");
    o.samples = settings.samples > 0 ? settings.samples : kSweepDefaultSamples;
    if (o.samples > 4096) fail(SS_ERROR_INVALID_ARGUMENT, "sweep: at most 4096 samples (got " + std::to_string(o.samples) + ")");
    o.seed = settings.seed;
    o.cancel = settings.cancel;
    o.memoryLimit = settings.memoryLimit;
    o.receiver = settings.text(kReceiver);
    const std::string fill = settings.choice(kFill);
    o.fill = fill == "smooth" ? planar::FillMode::Smooth : fill == "steps" ? planar::FillMode::Steps : planar::FillMode::Rings;
    o.borderShare = settings.number(kBorder);
    o.clusters = settings.integer(kClusters);
    const std::string passes = settings.choice(kPasses);
    o.passes = passes == "auto" ? 0 : std::stoi(passes);
    o.irradianceWeights = settings.choice(kWeights) == "irradiance";
    return o;
}

std::vector<LightCluster> splitLight(const Light& light, int clusters) {
    if (clusters <= 1) return {LightCluster{light, 1.0}};
    if (light.type != LightType::Square && light.type != LightType::Rectangle)
        fail(SS_ERROR_UNSUPPORTED, "sweep: setting 'clusters' needs a square or rectangle light ('" + light.name +
                                       "' is a " + lightTypeName(light.type) + " light)");
    // Equal strips of a uniform emitter send equal power: each weighs 1/clusters.
    const glm::vec3 ax = light.halfAxisX(), ay = light.halfAxisY();
    const bool alongX = glm::length(ax) >= glm::length(ay);
    const glm::vec3 axis = alongX ? ax : ay;
    std::vector<LightCluster> out;
    for (int k = 0; k < clusters; ++k) {
        LightCluster c{light, 1.0 / clusters};
        c.light.type = LightType::Rectangle;
        c.light.sizeY = light.type == LightType::Square ? light.size : light.sizeY;
        if (alongX) c.light.size = light.size / float(clusters);
        else c.light.sizeY /= float(clusters);
        float t = -1.0f + (2.0f * k + 1.0f) / float(clusters);
        c.light.lightToWorld[3] = glm::vec4(light.position() + t * axis, 1.0f);
        out.push_back(std::move(c));
    }
    return out;
}

int autoSweepPasses(const WidestPenumbra& widest, const Camera& camera, int samples) {
    if (!(widest.width > 0.0) || samples < 2) return 1;
    // Pixels per world unit at the penumbra's depth (foreshortening left out: it only narrows).
    const double scale = 0.5 * camera.height * std::abs(double(camera.projection[1][1]));
    double depth = 1.0;
    if (!camera.isOrthographic()) {
        depth = -(camera.worldToCamera * glm::vec4(glm::vec3(widest.at), 1.0f)).z;
        if (!(depth > 0.0)) return 1;  // behind the camera: not seen
    }
    const double pixels = widest.width * scale / depth;
    const double passes = std::ceil(pixels / (kSweepPixelsPerRing * samples));
    return int(std::clamp(std::isfinite(passes) ? passes : 1.0, 1.0, double(kSweepMaxPasses)));
}

namespace {

// The light's largest extent across (its diameter) and the widest penumbra its occluders cast:
// a point at height h under a light at height H casts a penumbra extent x h / (H - h) wide.
WidestPenumbra widestPenumbra(const Scene& scene, const Light& light, const ReceiverPlane& plane,
                              const std::vector<int>& occluders) {
    WidestPenumbra out;
    const bool sun = light.type == LightType::Sun;
    double extent = 0.0, lightHeight = 0.0;
    const glm::dvec3 centre(light.position());
    glm::dvec3 toLight(0.0);
    if (sun) {
        toLight = -glm::dvec3(light.direction());
        if (!(glm::dot(toLight, plane.normal) > 1e-6)) return out;
        extent = 2.0 * std::tan(light.sunHalfAngle()) / glm::dot(toLight, plane.normal);
    } else {
        extent = light.isArea() ? 2.0 * std::max(glm::length(light.halfAxisX()), glm::length(light.halfAxisY()))
                                : 2.0 * double(light.radius);
        lightHeight = plane.height(centre);
        if (!(lightHeight > 0.0)) return out;
    }
    for (int i : occluders)
        for (const glm::vec3& p : scene.meshes()[size_t(i)].positions) {
            const glm::dvec3 q(p);
            const double h = plane.height(q);
            if (!(h > 0.0)) continue;
            if (sun) {
                const double width = extent * h;
                if (width > out.width) out = {q - toLight * (h / glm::dot(toLight, plane.normal)), width};
                continue;
            }
            if (h >= 0.999 * lightHeight) continue;  // clipped by the projection, as there
            const double width = extent * h / (lightHeight - h);
            if (width > out.width) out = {centre + (q - centre) * (lightHeight / (lightHeight - h)), width};
        }
    return out;
}

// Refuses a shadow mesh whose triangles (with `held` of the clusters before it) are over the
// memory limit, before its weights are made: the fill is done by then, the largest part not.
void requireMeshWithinMemory(const Light& light, int64_t held, const planar::ShadowMesh& mesh, int samples,
                             const SweepOptions& options) {
    const int64_t triangles = held + int64_t(mesh.indices.size() / 3);
    const bool weighed = options.irradianceWeights && samples > 1;
    const double need = sweepMeshPeakBytes(held, 0, false) + sweepMeshPeakBytes(triangles - held, samples, weighed);
    char how[160];
    if (weighed)
        std::snprintf(how, sizeof how, "%.0f bytes a triangle + %.0f for each of its %d samples' weights and their sum",
                      kBudgetBytesPerSweepTriangle, kBudgetBytesPerSweepWeight, samples);
    else
        std::snprintf(how, sizeof how, "%.0f bytes a triangle", kBudgetBytesPerSweepTriangle);
    requireWithinMemory(options.memoryLimit, need,
                        "light '" + light.name + "': sweep's shadow mesh of " + std::to_string(triangles) +
                            " triangles from " + std::to_string(samples) + " light samples",
                        how, weighed ? "use fewer samples, or weights=equal" : "use fewer samples");
}

// One cluster's shadow mesh (intensities not yet weighted) and the samples it used; `held`:
// the triangles of the clusters' meshes made before it.
planar::ShadowMesh clusterShadow(const Scene& scene, int lightIndex, int cluster, const std::vector<int>& occluders,
                                 const Light& light, const LightSampleOptions& so, const SweepOptions& options,
                                 SweepProjectionCache& cache, SweepShadow* out, int* used, int64_t held) {
    std::vector<LightSample> usedSamples;
    for (const LightSample& s : placeLightSamples(light, so))
        if (castsOntoPlane(out->plane, s)) usedSamples.push_back(s);
    std::vector<std::vector<planar::DirectedEdge>> outlines;
    std::vector<planar::DirectedEdge> edges;
    SweepProjectionCache::Pass projections =
        cache.begin(lightIndex, cluster, scene, occluders, out->plane, out->snap, usedSamples);
    for (size_t s = 0; s < usedSamples.size(); ++s) {
        if (options.cancel && options.cancel->load(std::memory_order_relaxed))
            fail(SS_ERROR_CANCELLED, "cancelled during sweep: light samples");
        edges.clear();
        auto t0 = Clock::now();
        projections.append(s, &edges);
        out->timings.silhouettesMs += msSince(t0);
        auto t1 = Clock::now();
        outlines.push_back(planar::hardOutline(edges));
        out->timings.sweepMs += msSince(t1);
    }
    projections.finish(&out->projection);
    *used = int(outlines.size());
    if (outlines.empty()) return {};
    auto t2 = Clock::now();
    std::vector<planar::DirectedEdge> merged = planar::mergeOutlines(outlines);
    out->timings.mergeMs += msSince(t2);
    auto t3 = Clock::now();
    planar::ShadowMesh mesh = fillShadowParts(merged, *used, options.fill, projections.filledParts(), &out->filling);
    projections.filled();
    out->timings.fillMs += msSince(t3);
    requireMeshWithinMemory(scene.light(lightIndex), held, mesh, *used, options);
    if (options.irradianceWeights && *used > 1) {
        auto t4 = Clock::now();
        if (WeightedTriangles* kept = projections.weighted()) {
            weighShadowMesh(mesh, outlines, usedSamples, light, out->plane, out->snap, options.fill, *kept,
                            &out->weighting);
            projections.weighed();
        } else {
            weighShadowMesh(mesh, outlines, usedSamples, light, out->plane, out->snap, options.fill, &out->weighting);
        }
        out->timings.weightsMs += msSince(t4);
    }
    return mesh;
}

}  // namespace

SweepShadow computeSweepShadow(const Scene& scene, int lightIndex, const SweepOptions& options,
                               SweepProjectionCache* cache) {
    const Light& light = scene.light(lightIndex);
    SweepProjectionCache uncached(0);
    SweepProjectionCache& projections = cache ? *cache : uncached;
    std::vector<LightCluster> clusters = splitLight(light, options.clusters);
    SweepShadow out;
    out.plane = findReceiverPlane(scene, light, options.receiver);
    out.snap = planar::Snap(out.plane.cu, out.plane.cv, out.plane.half);
    std::vector<int> occluders = sweepOccluders(scene, lightIndex, out.plane);

    LightSampleOptions so;
    so.seed = options.seed;
    so.borderShare = options.borderShare;
    Bounds ob;
    for (int i : occluders)
        for (const glm::vec3& p : scene.meshes()[i].positions) ob.extend(p);
    so.viewFrom = ob.empty() ? out.plane.origin : glm::dvec3(ob.center());
    out.widest = widestPenumbra(scene, light, out.plane, occluders);
    out.passes = options.passes > 0 ? options.passes
                 : scene.hasCamera() ? autoSweepPasses(out.widest, scene.camera(), options.samples)
                                     : 1;
    if (clusters.size() == 1 && out.passes == 1) {
        so.count = options.samples;
        projections.keep(int(scene.lights().size()), lightIndex, 1);
        out.mesh = clusterShadow(scene, lightIndex, 0, occluders, light, so, options, projections, &out, &out.samplesUsed, 0);
        return out;
    }
    // Clusters and passes: each its own soft shadow from its share of the samples (at least
    // one), merged without interpolation: V = sum_k w_k V_k, i.e. intensities weighted and
    // added. Pass p of a cluster is a sample set of its own (seed offset), weighing 1/passes.
    // A cluster whose samples are all below the receiver's horizon sends nothing there; the
    // others' weights are renormalised so the part of the light that can reach still sums to one.
    projections.keep(int(scene.lights().size()), lightIndex, int(clusters.size()) * out.passes);
    std::vector<planar::ShadowMesh> meshes;
    std::vector<double> weights;
    double total = 0.0;
    int64_t held = 0;
    for (int p = 0; p < out.passes; ++p)
        for (size_t k = 0; k < clusters.size(); ++k) {
            so.count = std::max(1, int(std::lround(options.samples * clusters[k].weight)));
            so.seed = options.seed + uint32_t(k) * 7919u + uint32_t(p) * 104729u;
            so.set = p;
            so.sets = out.passes;
            int used = 0;
            const int set = p * int(clusters.size()) + int(k);
            planar::ShadowMesh m =
                clusterShadow(scene, lightIndex, set, occluders, clusters[k].light, so, options, projections, &out, &used, held);
            if (used == 0) continue;
            held += int64_t(m.indices.size() / 3);
            out.samplesUsed += used;
            total += clusters[k].weight;
            meshes.push_back(std::move(m));
            weights.push_back(clusters[k].weight);
        }
    for (size_t k = 0; k < meshes.size(); ++k) {
        planar::ShadowMesh& m = meshes[k];
        const float w = float(weights[k] / total);
        for (planar::ShadowVertex& v : m.vertices) v.intensity *= w;
        const uint32_t base = uint32_t(out.mesh.vertices.size());
        out.mesh.vertices.insert(out.mesh.vertices.end(), m.vertices.begin(), m.vertices.end());
        for (uint32_t i : m.indices) out.mesh.indices.push_back(base + i);
        out.mesh.umbraTriangles += m.umbraTriangles;
        out.mesh.penumbraTriangles += m.penumbraTriangles;
        // A point is in the merged umbra only if in every cluster's umbra, so these two are
        // bounds (the smallest cluster umbra from above; the union of the shadows from below by
        // the largest one), not the merged areas.
        out.mesh.umbraArea = k == 0 ? m.umbraArea : std::min(out.mesh.umbraArea, m.umbraArea);
        out.mesh.shadowArea = std::max(out.mesh.shadowArea, m.shadowArea);
        out.parts.push_back(std::move(m));
    }
    return out;
}

}  // namespace ss
