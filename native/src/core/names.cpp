// How names from user data are checked and quoted.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/names.h"

#include <cstdio>

#include "core/error.h"

namespace ss {

namespace {

// Length of the valid UTF-8 sequence starting at text[i], or 0.
size_t utf8Length(const std::string& text, size_t i) {
    auto byte = [&](size_t k) { return (unsigned char)text[k]; };
    unsigned char c = byte(i);
    if (c < 0x80) return 1;
    size_t n;
    unsigned min;
    unsigned cp;
    if ((c & 0xE0) == 0xC0) n = 2, min = 0x80, cp = c & 0x1F;
    else if ((c & 0xF0) == 0xE0) n = 3, min = 0x800, cp = c & 0x0F;
    else if ((c & 0xF8) == 0xF0) n = 4, min = 0x10000, cp = c & 0x07;
    else return 0;
    if (i + n > text.size()) return 0;
    for (size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (byte(i + k) & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return n;
}

}  // namespace

bool isValidUtf8(const std::string& text) {
    for (size_t i = 0; i < text.size();) {
        size_t n = utf8Length(text, i);
        if (n == 0) return false;
        i += n;
    }
    return true;
}

std::string quoted(const std::string& text) {
    std::string out = "'";
    for (size_t i = 0; i < text.size();) {
        size_t n = utf8Length(text, i);
        unsigned char c = (unsigned char)text[i];
        if (n == 0 || c < 0x20 || c == 0x7F) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", unsigned(c));
            out += buf;
            i += 1;
        } else {
            out.append(text, i, n);
            i += n;
        }
    }
    return out + "'";
}

void checkName(const std::string& what, const std::string& name, size_t maxBytes) {
    if (name.empty()) fail(SS_ERROR_INVALID_SCENE, "a " + what + " has an empty name");
    if (name.size() > maxBytes)
        fail(SS_ERROR_INVALID_SCENE, what + " name " + quoted(name) + " is " + std::to_string(name.size()) +
                                         " bytes long (at most " + std::to_string(maxBytes) + ")");
    if (!isValidUtf8(name))
        fail(SS_ERROR_INVALID_SCENE, what + " name " + quoted(name) + " is not valid UTF-8");
    for (unsigned char c : name)
        if (c < 0x20 || c == 0x7F)
            fail(SS_ERROR_INVALID_SCENE, what + " name " + quoted(name) +
                                             " has a control character (allowed: printable UTF-8)");
}

void checkViewLayerName(const std::string& name) {
    try {
        checkName("view layer", name, kMaxViewLayerBytes);
    } catch (const Error& e) {
        fail(SS_ERROR_INVALID_ARGUMENT, e.what());
    }
    if (name.find('.') != std::string::npos)
        fail(SS_ERROR_INVALID_ARGUMENT, "view layer name " + quoted(name) +
                                            " has a dot (Blender splits channel names at dots)");
}

}  // namespace ss
