// How a set of directed segments is swept left to right into vertical slabs in which no two
// segments cross, with the winding number of every gap.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <span>
#include <vector>

#include "planar/predicates.h"

namespace ss::planar {

// A directed edge of a shadow outline, "shadow on the right" (so a clockwise ring bounds its
// shadow). Its `weight` is how many times it counts (coincident copies, or a jump of 2).
struct DirectedEdge {
    IPoint a, b;
    int weight = 1;
};

// A swept segment: left to right, with the change of winding number when crossing it upward.
struct SweepSegment {
    ISeg seg;
    int delta = 0;
};

// Converts directed edges to sweep segments; vertical and zero-length edges are dropped
// because they change no winding number in any slab, and coincident segments are merged (their
// deltas summed, dropped when they cancel).
std::vector<SweepSegment> toSweepSegments(std::span<const DirectedEdge> edges);

// Coincident segments inside a slab form one group; `seg` is the group's first segment index.
struct SlabGroup {
    int seg = 0;
    int delta = 0;  // summed over the group
};

// Called once per slab [xl, xr] (xl < xr) that holds at least one segment, with its groups
// from bottom to top. Winding below group i = sum of delta of groups 0..i-1 (0 below all).
using SlabFn = std::function<void(const RatX& xl, const RatX& xr, std::span<const SlabGroup> groups)>;

struct SweepStats {
    size_t events = 0;
    size_t crossings = 0;
};

// The sweep: events at segment ends and at crossings of neighbours in the active list,
// which is kept ordered with exact predicates. Segments are split implicitly at slab borders.
SweepStats sweep(std::span<const SweepSegment> segments, const SlabFn& onSlab);

}  // namespace ss::planar
