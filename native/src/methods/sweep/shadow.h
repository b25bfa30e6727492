// What the sweep method computes on the CPU for one light: the light samples, each sample's
// hard outline, the merged rings and the shadow mesh on the receiver plane, with stage timings.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <atomic>
#include <string>
#include <vector>

#include "core/scene.h"
#include "methods/method.h"
#include "methods/sweep/projection.h"
#include "methods/sweep/projection_cache.h"
#include "methods/sweep/receiver.h"
#include "planar/penumbra_fill.h"

namespace ss {

constexpr int kSweepDefaultSamples = 16;

struct SweepOptions {
    int samples = kSweepDefaultSamples;
    uint32_t seed = 1;
    double borderShare = 0.25;
    planar::FillMode fill = planar::FillMode::Smooth;
    std::string receiver;  // mesh name; empty = the largest planar receiver
    // Square/rectangle lights split into this many equal convex strips along their longer side,
    // each shadowed on its own and merged without interpolation (paper 2, section 6).
    int clusters = 1;
    // Independent sample sets of `samples` each, swept apart and averaged (drawn additively like
    // clusters): each ring weighs 1/passes as much, so a wide penumbra's ring spacing, uneven
    // with few samples (the Gouraud bands), evens out at passes x the cost of one set, not the
    // near-quadratic cost of one set passes times larger. 0: chosen from the widest penumbra on
    // screen (autoSweepPasses).
    int passes = 1;
    // Each sample weighed by the irradiance it sends to each shadow-mesh corner (the contract);
    // false: every sample counts the same (the paper).
    bool irradianceWeights = true;
    // RenderSettings::cancel: checked between light samples (null: never cancelled).
    const std::atomic<bool>* cancel = nullptr;
    // RenderSettings::memoryLimit: the shadow mesh is refused once its triangles are known, before
    // its irradiance weights, when sweepMeshPeakBytes is over it (core/memory_budget.h).
    MemoryLimit memoryLimit;
};

// raster=gl: the shadow triangles drawn with the camera's matrices and resolved on the GPU;
// raster=cpu: the same triangles looked up per pixel over the camera pass read back (a cross-check).
inline constexpr SettingSpec kSweepRaster =
    choiceSetting("raster", "gl|cpu", "gl: draw the shadow mesh; cpu: look it up per pixel (a cross-check)");
// The settings the sweep reads (its shadow mesh and its camera pass).
const SettingTable& sweepSettings();
// Reads RenderSettings: samples (0 = 16), seed, options "receiver", "fill" (smooth|steps|rings),
// "border" (share of samples on the light's border, 0..1), "clusters" (1..64), "passes"
// (auto|1..16, default auto), "weights" (irradiance|equal). Throws ss::Error on a bad value;
// unknown keys are the caller's check (the renderer: the method's table and refinement's; the
// C API: sweepSettings()).
SweepOptions sweepOptions(const RenderSettings& settings);

struct SweepTimings {
    double silhouettesMs = 0, sweepMs = 0, mergeMs = 0, fillMs = 0;
    double weightsMs = 0;  // irradiance weights (not part of fillMs)
};

// A convex part of the light (the whole light when there is one cluster): its share of the
// light's emitted power and the light it stands for.
struct LightCluster {
    Light light;
    double weight = 1.0;
};

// The light cut into `clusters` equal strips along its longer side (square/rectangle lights);
// one cluster returns the light itself. Throws SS_ERROR_UNSUPPORTED for other shapes.
std::vector<LightCluster> splitLight(const Light& light, int clusters);

// Where the widest penumbra of the occluders falls on the receiver plane (world) and how wide it
// is there (world units): the highest occluder point's, light extent x h / (H - h).
struct WidestPenumbra {
    glm::dvec3 at{0.0};
    double width = 0.0;
};

// Passes for `samples` light samples per set so that the widest penumbra, seen by `camera`,
// holds at most kSweepPixelsPerRing pixels per ring over all sets; 1 to kSweepMaxPasses.
constexpr double kSweepPixelsPerRing = 1.0;
constexpr int kSweepMaxPasses = 4;
int autoSweepPasses(const WidestPenumbra& widest, const Camera& camera, int samples);

struct SweepShadow {
    ReceiverPlane plane;
    planar::Snap snap{0, 0, 1};
    // Grid coordinates. With one cluster the triangles tile the shadow (no overlaps). With
    // several, this is every cluster's mesh, intensities already multiplied by its weight,
    // concatenated: the triangles of different clusters overlap and their intensities ADD
    // (V = 1 - sum_k w_k I_k, no interpolation between clusters); `parts` holds them apart.
    planar::ShadowMesh mesh;
    std::vector<planar::ShadowMesh> parts;  // empty with one cluster
    int samplesUsed = 0;            // samples above the receiver plane, over every pass
    int passes = 1;                 // sample sets averaged (SweepOptions::passes, resolved)
    WidestPenumbra widest;
    ProjectionStats projection;
    WeightStats weighting;  // irradiance weights: triangles weighed, and reused from the cache
    FillStats filling;      // parts of the shadow filled, and reused from the cache
    SweepTimings timings;
    // World position of a shadow-mesh vertex.
    glm::dvec3 worldVertex(size_t i) const {
        return plane.toWorld(snap.toU(mesh.vertices[i].x), snap.toV(mesh.vertices[i].y));
    }
};

// `cache` (may be null: nothing kept) holds each occluder's projections from earlier shadows of
// this light: meshes whose version, receiver plane and samples are unchanged are not projected
// again (projection.meshesReused counts them), parts of the shadow whose edges did not change are
// not filled again (filling.partsReused), and shadow triangles away from what changed keep their
// irradiance weights (weighting.trianglesReused); the result is the same either way, bit for bit.
SweepShadow computeSweepShadow(const Scene& scene, int lightIndex, const SweepOptions& options,
                               SweepProjectionCache* cache = nullptr);

}  // namespace ss
