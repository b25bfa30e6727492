// How an output file is written under a temporary name in its folder and renamed into place,
// so no reader ever sees a half-written file and a failure leaves nothing behind.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <functional>
#include <string>

namespace ss {

// Calls write(tempPath) with a fresh name in the folder of `path` (keeping its extension), then
// renames the result over `path`. When write throws, or the rename fails, the temporary file is
// removed and ss::Error(SS_ERROR_IO) names `path` (write's own ss::Error passes through).
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace ss
