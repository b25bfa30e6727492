// How the sweep method's CPU stages run in order: samples, projection, per-sample sweep,
// merge and fill.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/shadow.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
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
constexpr SettingSpec kWeights =
    choiceSetting("weights", "irradiance|equal", "sample weights: by irradiance, or equal (the paper)");

}  // namespace

const SettingTable& sweepSettings() {
    static const SettingTable table{kReceiver, kFill, kBorder, kClusters, kWeights, kSweepRaster};
    return table;
}

SweepOptions sweepOptions(const RenderSettings& settings) {
    SweepOptions o;
    if (settings.samples < 0) fail(SS_ERROR_INVALID_ARGUMENT, "sweep: samples must not be negative");
    o.samples = settings.samples > 0 ? settings.samples : kSweepDefaultSamples;
    if (o.samples > 4096) fail(SS_ERROR_INVALID_ARGUMENT, "sweep: at most 4096 samples (got " + std::to_string(o.samples) + ")");
    o.seed = settings.seed;
    o.cancel = settings.cancel;
    o.receiver = settings.text(kReceiver);
    const std::string fill = settings.choice(kFill);
    o.fill = fill == "smooth" ? planar::FillMode::Smooth : fill == "steps" ? planar::FillMode::Steps : planar::FillMode::Rings;
    o.borderShare = settings.number(kBorder);
    o.clusters = settings.integer(kClusters);
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

namespace {

// One cluster's shadow mesh (intensities not yet weighted) and the samples it used.
planar::ShadowMesh clusterShadow(const Scene& scene, int lightIndex, int cluster, const std::vector<int>& occluders,
                                 const Light& light, const LightSampleOptions& so, const SweepOptions& options,
                                 SweepProjectionCache& cache, SweepShadow* out, int* used) {
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
    projections.keep(int(scene.lights().size()), lightIndex, int(clusters.size()));
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
    if (clusters.size() == 1) {
        so.count = options.samples;
        out.mesh = clusterShadow(scene, lightIndex, 0, occluders, light, so, options, projections, &out, &out.samplesUsed);
        return out;
    }
    // Clusters: each its own soft shadow from its share of the samples (at least one), merged
    // without interpolation: V = sum_k w_k V_k, i.e. intensities weighted and added. A cluster
    // whose samples are all below the receiver's horizon sends nothing there; the others'
    // weights are renormalised so the part of the light that can reach still sums to one.
    std::vector<planar::ShadowMesh> meshes;
    std::vector<double> weights;
    double total = 0.0;
    for (size_t k = 0; k < clusters.size(); ++k) {
        so.count = std::max(1, int(std::lround(options.samples * clusters[k].weight)));
        so.seed = options.seed + uint32_t(k) * 7919u;
        int used = 0;
        planar::ShadowMesh m =
            clusterShadow(scene, lightIndex, int(k), occluders, clusters[k].light, so, options, projections, &out, &used);
        if (used == 0) continue;
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
