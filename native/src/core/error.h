// How failures travel inside the library: one exception type carrying the C API status.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <stdexcept>
#include <string>

#include "softshadow/softshadow.h"

namespace ss {

class Error : public std::runtime_error {
public:
    Error(ss_status status, const std::string& message)
        : std::runtime_error(message), status_(status) {}
    ss_status status() const { return status_; }

private:
    ss_status status_;
};

[[noreturn]] inline void fail(ss_status status, const std::string& message) {
    throw Error(status, message);
}

// `index` as a size_t when 0 <= index < count; else fails with SS_ERROR_INVALID_ARGUMENT in the
// one wording every index check uses: "<where>: light index 5 is out of range (the scene has
// 2 lights)" (no "<where>: " when `where` is empty).
inline size_t checkedIndex(int index, size_t count, const std::string& where, const char* item, const char* items,
                           const char* holder) {
    if (index < 0 || size_t(index) >= count)
        fail(SS_ERROR_INVALID_ARGUMENT, (where.empty() ? "" : where + ": ") + item + " index " + std::to_string(index) +
                                            " is out of range (the " + holder + " has " + std::to_string(count) +
                                            " " + items + ")");
    return size_t(index);
}

}  // namespace ss
