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

// The code point of the valid n-byte UTF-8 sequence at text[i].
unsigned codePoint(const std::string& text, size_t i, size_t n) {
    static const unsigned kLeadMask[] = {0, 0x7F, 0x1F, 0x0F, 0x07};
    unsigned cp = (unsigned char)text[i] & kLeadMask[n];
    for (size_t k = 1; k < n; ++k) cp = (cp << 6) | ((unsigned char)text[i + k] & 0x3F);
    return cp;
}

}  // namespace

bool isControlOrBidi(unsigned cp) {
    return cp < 0x20 || (cp >= 0x7F && cp <= 0x9F) || cp == 0x061C || cp == 0x200E || cp == 0x200F ||
           (cp >= 0x202A && cp <= 0x202E) || (cp >= 0x2066 && cp <= 0x2069);
}

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
        if (n == 0 || (n == 1 && isControlOrBidi(c))) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", unsigned(c));
            out += buf;
            i += 1;
        } else if (isControlOrBidi(codePoint(text, i, n))) {
            char buf[12];
            std::snprintf(buf, sizeof buf, "\\u%04X", codePoint(text, i, n));
            out += buf;
            i += n;
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
    for (size_t i = 0; i < name.size();) {
        size_t n = utf8Length(name, i);
        if (isControlOrBidi(codePoint(name, i, n)))
            fail(SS_ERROR_INVALID_SCENE, what + " name " + quoted(name) +
                                             " has a control character or a bidirectional formatting "
                                             "character (allowed: printable UTF-8)");
        i += n;
    }
}

std::string passToken(const std::string& name) {
    std::string out = name;
    for (char& c : out)
        if (c == '.' || c == ' ') c = '_';
    return out;
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
