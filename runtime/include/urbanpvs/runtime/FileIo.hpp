// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The file helpers of the runtime: read a whole file into memory, and the one atomic writer
/// that every urbanpvs tool writes its outputs with (.pvs files, reports, cities, SVG maps).
/// Engines with their own file systems (pak files, memory mapping) skip them and call
/// PvsFile::open on their bytes.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "urbanpvs/runtime/Status.hpp"

namespace urbanpvs::runtime {

/// Replaces `out` with the contents of the file at `path`. kIoError when it cannot be opened or
/// read (out is then empty), kOutOfMemory when the buffer cannot be allocated. Works on regular
/// files and pipes. Standard library only (std::FILE), so no memory mapping.
Status read_file(const char* path, std::vector<std::byte>& out) noexcept;

/// A file that cannot be written; what() is "<path>: <reason>".
class FileWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writes `size` bytes to `path` atomically: to a temporary file in the same directory
/// ("<path>.tmp-<random>", so concurrent writers stay apart), then renamed over `path`, so
/// readers see the old or the new file, never a partial one. Throws FileWriteError on failure
/// and removes the temporary file. Uses only the standard library, so the data is not fsync'ed.
void write_file_atomic(const std::string& path, const void* data, std::size_t size);
inline void write_file_atomic(const std::string& path, const std::vector<std::byte>& bytes) {
  write_file_atomic(path, bytes.data(), bytes.size());
}
inline void write_file_atomic(const std::string& path, std::string_view text) {
  write_file_atomic(path, text.data(), text.size());
}

}  // namespace urbanpvs::runtime
