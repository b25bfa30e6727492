// How a JSON text is parsed strictly, so that every problem names its JSON path: malformed text,
// numbers that overflow, duplicate keys, NUL characters in strings, nesting too deep.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace ss {

// Deeper nesting is refused before it can exhaust the stack.
inline constexpr size_t kMaxJsonDepth = 64;

// Throws ss::Error(SS_ERROR_IO) "<where>: <path>: <problem>" (path as in meshes[2].positions[7]).
nlohmann::json parseJsonStrict(const std::string& text, const std::string& where);

}  // namespace ss
