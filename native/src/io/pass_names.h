// How (light, method, layer) become the EXR pass and channel names Blender lists (docs/contracts.md
// "EXR files"), and how a pass name is split back into its parts.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

namespace ss {

// passToken (core/names.h): dots and spaces become "_".
std::string sanitizePassToken(const std::string& text);

// "<light>_<method>" for the main layer "V", "<light>_<method>_<layer>" for the others.
std::string passName(const std::string& light, const std::string& method, const std::string& layer);

// "<view_layer>.<pass>.V": Blender takes the last token as the channel, the one before as the
// pass, and everything before that as the layer.
std::string channelName(const std::string& viewLayer, const std::string& pass);

// A pass name split at the right-most "_<known method>" (or "_auto") that ends the name or is
// followed by "_": light (sanitized), method, layer ("V" for the main pass). False when no method
// matches.
struct PassParts {
    std::string light, method, layer;
};
bool splitPassName(const std::string& pass, PassParts* out);

}  // namespace ss
