// What "umbra", "penumbra" and "lit" mean: the one classification of a visibility value that
// the layers, the metrics and the docs share (docs/architecture.md, "Visibility classes").
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "core/image.h"

namespace ss {

// A pixel is umbra when V < kUmbraThreshold, lit when V > kLitThreshold, penumbra in between
// (both ends included). Only pixels inside the mask have a class.
inline constexpr float kUmbraThreshold = 0.05f;
inline constexpr float kLitThreshold = 0.95f;

inline bool isUmbra(float v) { return v < kUmbraThreshold; }
inline bool isLit(float v) { return v > kLitThreshold; }
inline bool isPenumbra(float v) { return v >= kUmbraThreshold && v <= kLitThreshold; }

// Adds "umbra" and "penumbra" (1 where the class holds inside mask > 0.5, else 0) right after
// the "mask" layer, from the "V" and "mask" layers. Every method's class layers come from here.
void addClassLayers(Layers& layers);

}  // namespace ss
