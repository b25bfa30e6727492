// Which filled parts of a light's shadow the last fill left, so that a move fills again only the
// parts of the shadow it reached.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <span>
#include <vector>

#include "planar/penumbra_fill.h"
#include "planar/sweep_line.h"

namespace ss {

// The parts (planar::separateShadowParts) of one light's last shadow and their meshes, with the
// sample count and fill they were made for.
struct FilledParts {
    int samples = 0;
    planar::FillMode fill = planar::FillMode::Smooth;
    struct Part {
        std::vector<planar::DirectedEdge> edges;
        planar::ShadowMesh mesh;
    };
    std::vector<Part> parts;
    size_t bytes() const;
    void clear() { std::vector<Part>().swap(parts); }
};

// Parts filled by one call, and those taken from FilledParts instead.
struct FillStats {
    size_t partsFilled = 0, partsReused = 0;
};

// The shadow mesh of the merged outlines of `samples` samples: each part filled on its own
// (planar::fillShadow) and the meshes concatenated in the parts' order. A part whose edges
// `kept` (may be null) holds from a call with the same samples and fill is taken from it, so
// the result is the same bit for bit; `kept` is left with this call's parts when there are
// several (a shadow of one part is filled again whenever it changes).
planar::ShadowMesh fillShadowParts(std::span<const planar::DirectedEdge> merged, int samples, planar::FillMode fill,
                                   FilledParts* kept, FillStats* stats);

}  // namespace ss
