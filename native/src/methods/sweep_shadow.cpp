// How the sweep method's CPU stages run in order: samples, projection, per-sample sweep,
// merge and fill.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep_shadow.h"

#include <chrono>

#include "core/error.h"
#include "planar/outline.h"
#include "planar/rings.h"
#include "sampling/light_samples.h"

namespace ss {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
}  // namespace

SweepOptions sweepOptions(const RenderSettings& settings) {
    SweepOptions o;
    if (settings.samples < 0) fail(SS_ERROR_INVALID_ARGUMENT, "sweep: samples must not be negative");
    o.samples = settings.samples > 0 ? settings.samples : kSweepDefaultSamples;
    if (o.samples > 4096) fail(SS_ERROR_INVALID_ARGUMENT, "sweep: at most 4096 samples (got " + std::to_string(o.samples) + ")");
    o.seed = settings.seed;
    o.receiver = settings.text("receiver", "");
    std::string fill = settings.text("fill", "smooth");
    if (fill == "smooth") o.fill = planar::FillMode::Smooth;
    else if (fill == "steps") o.fill = planar::FillMode::Steps;
    else fail(SS_ERROR_INVALID_ARGUMENT, "sweep: setting 'fill' = '" + fill + "' is not smooth or steps");
    o.borderShare = settings.number("border", 0.25f);
    if (!(o.borderShare >= 0 && o.borderShare <= 1))
        fail(SS_ERROR_INVALID_ARGUMENT, "sweep: setting 'border' must be in [0, 1]");
    return o;
}

SweepShadow computeSweepShadow(const Scene& scene, int lightIndex, const SweepOptions& options) {
    if (lightIndex < 0 || size_t(lightIndex) >= scene.lights().size())
        fail(SS_ERROR_INVALID_ARGUMENT, "sweep: light index " + std::to_string(lightIndex) + " is out of range");
    const Light& light = scene.lights()[lightIndex];
    SweepShadow out;
    out.plane = findReceiverPlane(scene, light, options.receiver);
    out.snap = planar::Snap(out.plane.cu, out.plane.cv, out.plane.half);
    std::vector<int> occluders = sweepOccluders(scene, out.plane);

    LightSampleOptions so;
    so.count = options.samples;
    so.seed = options.seed;
    so.borderShare = options.borderShare;
    Bounds ob;
    for (int i : occluders)
        for (const glm::vec3& p : scene.meshes()[i].positions) ob.extend(p);
    so.viewFrom = ob.empty() ? out.plane.origin : glm::dvec3(ob.center());
    std::vector<LightSample> samples = placeLightSamples(light, so);

    std::vector<std::vector<planar::DirectedEdge>> outlines;
    std::vector<planar::DirectedEdge> edges;
    for (const LightSample& s : samples) {
        edges.clear();
        auto t0 = Clock::now();
        if (!projectSample(scene, occluders, out.plane, out.snap, s, &edges, &out.projection)) continue;
        out.timings.silhouettesMs += msSince(t0);
        auto t1 = Clock::now();
        outlines.push_back(planar::hardOutline(edges));
        out.timings.sweepMs += msSince(t1);
    }
    out.samplesUsed = int(outlines.size());
    if (outlines.empty()) return out;
    auto t2 = Clock::now();
    std::vector<planar::DirectedEdge> merged = planar::mergeOutlines(outlines);
    out.timings.mergeMs = msSince(t2);
    auto t3 = Clock::now();
    out.mesh = planar::fillShadow(merged, out.samplesUsed, options.fill);
    out.timings.fillMs = msSince(t3);
    return out;
}

}  // namespace ss
