// How a native test renders light 0 of a scene with one method, and takes one layer of the result.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <map>
#include <stdexcept>
#include <string>

#include "core/image.h"
#include "core/scene.h"
#include "core/settings.h"
#include "renderer/renderer.h"

namespace ss::test {

// Light 0 of `scene` rendered with `method` ("auto" too), `samples` light samples (0: the
// method's default) and `options` as the method's settings; every layer.
inline Layers run(Renderer& renderer, const Scene& scene, const std::string& method, int samples = 0,
                  const std::map<std::string, std::string>& options = {}) {
    RenderSettings settings;
    settings.samples = samples;
    settings.options = options;
    std::string used;
    return renderer.render(scene, 0, method, settings, &used);
}

// The layer called `name`; a result without it throws, which fails the test naming the layer.
inline const Image& layer(const Layers& layers, const char* name) {
    const Image* image = layers.find(name);
    if (!image) throw std::runtime_error(std::string("missing layer ") + name);
    return *image;
}

}  // namespace ss::test
