// Where the benchmark binary starts: Google Benchmark's main plus joining the render threads
// (every bench/*.cpp registers its benchmarks; none defines main).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <benchmark/benchmark.h>

#include "gl/render_thread.h"

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    ss::shutdownRenderThreads();
    return 0;
}
