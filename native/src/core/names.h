// Which names a scene accepts for lights, meshes and the view layer, and how a name from user
// data is shown in a message without its control characters reaching the terminal.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

namespace ss {

// Blender's own limit for an object or view layer name (MAX_NAME - 1), in bytes.
constexpr size_t kMaxViewLayerBytes = 63;
// A light or mesh: a Blender name, or an instance's "<parent>/<object>" with a ".NNN" suffix
// (63 + 1 + 63 + 4). The longest EXR channel such a light gets stays within EXR's 255 bytes.
constexpr size_t kMaxNameBytes = 131;

// Throws ss::Error(SS_ERROR_INVALID_SCENE) naming `what` (e.g. "light") unless `name` is
// 1..maxBytes bytes of valid UTF-8 without control or bidirectional formatting characters
// (isControlOrBidi).
void checkName(const std::string& what, const std::string& name, size_t maxBytes = kMaxNameBytes);

// A name as it appears in EXR pass names: dots and spaces become "_" (Blender splits channel
// names at dots). Two lights whose tokens are equal would write the same passes.
std::string passToken(const std::string& name);

// As checkName("view layer", ..., kMaxViewLayerBytes), and no dot (Blender splits channel names at dots); throws
// ss::Error(SS_ERROR_INVALID_ARGUMENT).
void checkViewLayerName(const std::string& name);

// Unicode's control characters (C0, DEL, C1) and the bidirectional formatting characters
// (U+061C, U+200E, U+200F, U+202A..U+202E, U+2066..U+2069), which reorder what a terminal or a
// file browser shows around them.
bool isControlOrBidi(unsigned codePoint);

// `text` between single quotes with invalid UTF-8 bytes and ASCII controls written as \xNN, the
// other isControlOrBidi characters as \uNNNN.
std::string quoted(const std::string& text);

// True when `text` is valid UTF-8 (no overlong forms, no surrogates).
bool isValidUtf8(const std::string& text);

}  // namespace ss
