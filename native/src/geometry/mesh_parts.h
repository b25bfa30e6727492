// Which separate parts a mesh's silhouettes are taken over: its vertices welded by position where
// it has open edges, then its connected pieces.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>
#include <vector>

#include "core/mesh.h"

namespace ss {

// The mesh's parts, each finalized (adjacency, normals), world positions, the mesh's flags. A
// mesh with open edges is first welded: vertices at exactly the same position become one (a
// flat-shaded export splits every hard edge, which makes each face of a box an open patch and
// every one of its edges a silhouette). The welded mesh is then split into its connected pieces
// (faces joined through shared edges), at most `maxParts`: beyond that the whole welded mesh
// is one part. Empty when the mesh itself is already the one part (closed or nothing to weld,
// and connected): the caller uses it as it is.
std::vector<Mesh> meshParts(const Mesh& mesh, size_t maxParts = 4096);

}  // namespace ss
