// Which GL passes make occlusion_textures: slicing the casters into packed occlusion textures.
// SPDX-License-Identifier: GPL-3.0-or-later
// And shading the camera G-buffer from the pre-filtered slices.
#pragma once
#include "core/image.h"
#include "scene_cache/moved_region.h"
#include "methods/occlusion_textures/prefilter.h"
#include "methods/occlusion_textures/slicing.h"

namespace ss {
class SceneCache;
}

namespace ss::occlusion {

// Light-local coordinates (x along axisX, y along axisY, z depth below the light) as a matrix.
glm::mat4 worldToLocal(const KernelLight& light);

// One draw of every casting mesh from the offset camera; a fragment sets its slice's channel
// (and the next one for thin meshes, or every mesh when thinFixAll).
SliceTextures renderSlices(SceneCache& sceneCache, const SliceSetup& setup, Filter filter, bool thinFixAll);
// The same draw into slices drawn before with `setup`, inside `rect` (slice texels, GL
// orientation) only: after moves, where the moved meshes were and are (movedBoxes,
// boxesOnScreen). MAX blending makes the result the whole draw's bit for bit.
void patchSlices(SceneCache& sceneCache, const SliceSetup& setup, SliceTextures& slices, bool thinFixAll, const PixelRect& rect);

struct ShadeOutput {
    Image visibility, mask;
    std::vector<Image> slices;  // camera-aligned w_k I_k, when requested
};
// skipEmptySlices: leave out the pixels and (SAT) the slices whose occupied texels no kernel
// reaches (exact; off only to show that in a test).
ShadeOutput shade(SceneCache& sceneCache, int lightIndex, const SliceSetup& setup, const FilteredSlices& filtered,
                  Fade fade, bool sliceLayers, bool skipEmptySlices);

}  // namespace ss::occlusion
