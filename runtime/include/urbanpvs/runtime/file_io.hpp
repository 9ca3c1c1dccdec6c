// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The one file helper of the runtime: read a whole file into memory. Engines with their own
/// file systems (pak files, memory mapping) skip it and call PvsFile::open on their bytes.

#include <cstddef>
#include <vector>

#include "urbanpvs/runtime/status.hpp"

namespace urbanpvs::runtime {

/// Replaces `out` with the contents of the file at `path`. kIoError when it cannot be opened or
/// read (out is then empty), kOutOfMemory when the buffer cannot be allocated. Works on regular
/// files and pipes. Standard library only (std::FILE), so no memory mapping.
Status read_file(const char* path, std::vector<std::byte>& out) noexcept;

}  // namespace urbanpvs::runtime
