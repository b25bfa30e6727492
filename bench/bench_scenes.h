// Which scenes the stage benchmarks draw, and the renderer and stage clock they share.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/glm.hpp>

#include "core/light.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "methods/method.h"
#include "renderer/renderer.h"

namespace ss::bench {

// A closed UV sphere with 4 m² triangles (poles as fans), radius r at c, outward winding:
// m = 16, 35, 50, 71, 112, 158, 274, 354, 500 give 1k, 4.9k, 10k, 20k, 50k, 100k, 300k, 500k, 1M
// triangles.
Mesh uvSphere(int m, float r, glm::vec3 c, uint32_t flags);
// An upward square of half size `half` at z = 0, casting and receiving.
Mesh groundSquare(float half);

// The stage benchmarks' scene: the sphere (m, flags) of radius 0.8 at height 1.3 over a ground
// square, lit by a light 4 up and off to the side (a 1.5 disk, or a 1.5 x 1.0 rectangle), seen
// from above at resolution².
Scene sphereOverGround(int m, uint32_t sphereFlags, LightType light, int resolution);

// A CAD-like assembly of 54 separate parts over a ground square, under the stage benchmarks'
// disk light, seen from above at resolution²: a base plate, two walls standing on it, a shaft
// through both with five discs, 24 standing pins, 12 thin fins, 8 rods across the top and a
// cover resting on a wall, the pins, rods, shaft and discs of 24, 12, 24 and 32 segments times
// `tessellation` (a fine CAD export: long silhouettes of short edges).
Scene assembly(int tessellation, int resolution);

// One renderer for the whole benchmark binary (GL started once); joined at exit.
Renderer& sharedRenderer();

// Progress marks of one render: `settings` with a progress callback that records when each
// stage began (methods call glFinish before each mark with debug.finish_stages=1).
struct StageClock {
    using Clock = std::chrono::steady_clock;
    std::map<std::string, Clock::time_point> marks;
    RenderSettings watch(const RenderSettings& settings);
    // Renders light 0 of `scene` with `method` on the shared renderer, marks recorded; seconds.
    double render(const Scene& scene, const std::string& method, const RenderSettings& settings);
    // Milliseconds from the mark `from` to the mark `to`.
    double ms(const std::string& from, const std::string& to) const;
};

// A span between two progress marks, reported as the counter `name` (ms, mean over iterations).
struct StageSpan {
    const char* name;
    const char* from;
    const char* to;
};
// The benchmark loop of a stage benchmark: each iteration runs `beforeEach` (when given), then
// renders light 0 of `scene` (manual time), and the spans' means become counters.
void timeStages(benchmark::State& state, const Scene& scene, const std::string& method,
                const RenderSettings& settings, const std::vector<StageSpan>& spans,
                const std::function<void()>& beforeEach = {});

}  // namespace ss::bench
