// How a single-channel float image aligned with the camera is stored (row 0 = top row).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <deque>
#include <string>
#include <utility>
#include <vector>

namespace ss {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> pixels;  // row-major, row 0 is the top of the picture

    Image() = default;
    Image(int w, int h, float fill = 0.0f) : width(w), height(h), pixels(size_t(w) * h, fill) {}
    float& at(int x, int y) { return pixels[size_t(y) * width + x]; }
    float at(int x, int y) const { return pixels[size_t(y) * width + x]; }
};

// The named outputs of one (light, method) render, in the order they were produced.
// Contract names: "V", "mask", "umbra", "penumbra"; methods add their own debug layers.
struct Layers {
    // A deque so the reference add() returns stays valid while more layers are added.
    std::deque<std::pair<std::string, Image>> items;

    Image& add(const std::string& name, Image image) {
        items.emplace_back(name, std::move(image));
        return items.back().second;
    }
    const Image* find(const std::string& name) const {
        for (auto& [n, img] : items)
            if (n == name) return &img;
        return nullptr;
    }
};

}  // namespace ss
