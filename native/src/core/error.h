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

}  // namespace ss
