// How the umbra and penumbra layers are drawn from V and the mask (one rule for every method).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/visibility_classes.h"

#include <iterator>

#include "core/error.h"

namespace ss {

void addClassLayers(Layers& layers) {
    const Image* v = layers.find("V");
    const Image* mask = layers.find("mask");
    if (!v || !mask) fail(SS_ERROR_INTERNAL, "umbra/penumbra layers need the V and mask layers");
    Image umbra(v->width, v->height, 0.0f), penumbra(v->width, v->height, 0.0f);
    for (size_t i = 0; i < v->pixels.size(); ++i) {
        if (!(mask->pixels[i] > 0.5f)) continue;
        umbra.pixels[i] = isUmbra(v->pixels[i]) ? 1.0f : 0.0f;
        penumbra.pixels[i] = isPenumbra(v->pixels[i]) ? 1.0f : 0.0f;
    }
    auto at = layers.items.begin();
    while (at != layers.items.end() && at->first != "mask") ++at;
    at = layers.items.insert(std::next(at), {"umbra", std::move(umbra)});
    layers.items.insert(std::next(at), {"penumbra", std::move(penumbra)});
}

}  // namespace ss
