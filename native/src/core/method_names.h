// Which shadow methods the library has, by their contract names (the names passes carry).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>
#include <vector>

namespace ss {

// The contract names, in a fixed order (fastest first, the reference last); "auto" is not one.
// methods/registry.cpp makes each; the C API hands the list to the add-on (ss_method_name).
const std::vector<std::string>& methodNames();
bool isMethodName(const std::string& name);

}  // namespace ss
