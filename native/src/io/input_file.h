// How an input file (a scene, an external mesh array) is read whole within a size limit: only
// regular files, sized before anything is allocated, and every refusal naming the file.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <string>

namespace ss {

// Reads the regular file at `path`. `what` names it in messages ("scene file", ...). Throws
// ss::Error(SS_ERROR_IO) "<what> '<path>' <problem>": does not exist, path too long, symlink
// loop, not a regular file (a folder, FIFO, device...), larger than maxBytes, unreadable.
std::string readInputFile(const std::string& path, const std::string& what, uint64_t maxBytes);

// The same checks without reading, for files another library opens; returns the size in bytes.
uint64_t checkInputFile(const std::string& path, const std::string& what);

}  // namespace ss
