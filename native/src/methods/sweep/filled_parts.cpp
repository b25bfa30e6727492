// How a shadow is filled part by part, a part whose edges did not change taken from the last fill.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "methods/sweep/filled_parts.h"

#include <cstdint>
#include <unordered_map>
#include <utility>

#include "planar/shadow_parts.h"

namespace ss {

namespace {

uint64_t hashEdges(std::span<const planar::DirectedEdge> edges) {
    uint64_t h = 1469598103934665603ull;
    for (const planar::DirectedEdge& e : edges)
        for (int64_t v : {e.a.x, e.a.y, e.b.x, e.b.y, int64_t(e.weight)}) h = (h ^ uint64_t(v)) * 1099511628211ull;
    return h;
}

void append(planar::ShadowMesh& into, const planar::ShadowMesh& part) {
    const uint32_t base = uint32_t(into.vertices.size());
    into.vertices.insert(into.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (uint32_t i : part.indices) into.indices.push_back(base + i);
    into.umbraTriangles += part.umbraTriangles;
    into.penumbraTriangles += part.penumbraTriangles;
    into.umbraArea += part.umbraArea;
    into.shadowArea += part.shadowArea;
    into.ringFallbacks += part.ringFallbacks;
}

}  // namespace

size_t FilledParts::bytes() const {
    size_t n = parts.capacity() * sizeof(Part);
    for (const Part& p : parts)
        n += p.edges.capacity() * sizeof(planar::DirectedEdge) +
             p.mesh.vertices.capacity() * sizeof(planar::ShadowVertex) + p.mesh.indices.capacity() * sizeof(uint32_t);
    return n;
}

planar::ShadowMesh fillShadowParts(std::span<const planar::DirectedEdge> merged, int samples, planar::FillMode fill,
                                   FilledParts* kept, FillStats* stats) {
    std::unordered_multimap<uint64_t, size_t> earlier;
    if (kept && kept->samples == samples && kept->fill == fill)
        for (size_t i = 0; i < kept->parts.size(); ++i) earlier.emplace(hashEdges(kept->parts[i].edges), i);
    std::vector<FilledParts::Part> now;
    for (std::vector<planar::DirectedEdge>& edges : planar::separateShadowParts(merged)) {
        FilledParts::Part part;
        auto [from, to] = earlier.equal_range(hashEdges(edges));
        for (auto it = from; it != to; ++it) {
            FilledParts::Part& old = kept->parts[it->second];
            if (!old.edges.empty() && planar::sameEdges(old.edges, edges)) {
                part = std::move(old);
                old.edges.clear();  // taken
                break;
            }
        }
        if (part.edges.empty()) {
            part.mesh = planar::fillShadow(edges, samples, fill);
            part.edges = std::move(edges);
            if (stats) ++stats->partsFilled;
        } else if (stats) {
            ++stats->partsReused;
        }
        now.push_back(std::move(part));
    }
    if (kept) kept->clear();
    // One part changes with every change of the shadow: nothing to keep it for.
    if (now.size() == 1) return std::move(now[0].mesh);
    planar::ShadowMesh mesh;
    for (const FilledParts::Part& p : now) append(mesh, p.mesh);
    if (kept) {
        kept->samples = samples;
        kept->fill = fill;
        kept->parts = std::move(now);
    }
    return mesh;
}

}  // namespace ss
