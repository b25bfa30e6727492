// Which code-built CAD-like assembly the many-parts quality tests render: dozens of separate,
// touching and interpenetrating closed parts and open shells over a ground plane.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstddef>

#include "core/scene.h"
#include "test_scenes.h"

namespace ss::test {

struct AssemblyParams {
    SceneParams scene;
    // Every part in one mesh (a CAD file imported as one object) instead of one mesh per part.
    bool oneMesh = false;
    // Vertices split where the surface turns by more than 30 degrees (what a glTF or a CAD
    // export with flat-shaded faces gives): each planar face of a box is its own open patch.
    bool splitHardEdges = false;
    // Cylinders get this many times their default segments (12 to 32): a finer CAD export.
    int tessellation = 1;
};

// A machine-like assembly of `assemblyParts()` parts, 0.6 to 1.45 above the ground, under the
// shared disk light: a base plate, two side walls standing on it (shared faces), a shaft through
// both walls with discs on it (interpenetrating), a row of thin fins, stacked blocks sharing
// faces, bolts sunk into a cover plate, L brackets of two interpenetrating boxes, and open shells
// (tubes without caps, a tray without a lid, a U channel). Parts cast; only the ground receives.
Scene sceneAssembly(const AssemblyParams& p = {});
size_t assemblyParts();

}  // namespace ss::test
