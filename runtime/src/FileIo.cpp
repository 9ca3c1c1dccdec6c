// SPDX-License-Identifier: MIT
// Whole-file reading (runtime) and atomic writing (writer), with the standard library only.
#include "urbanpvs/runtime/FileIo.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <random>
#include <string>
#include <system_error>

#include "HugePages.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::runtime {

namespace {

/// The whole file at `path` into `out` (any vector of bytes).
template <class Bytes>
Status read_whole_file(const char* path, Bytes& out) noexcept {
  out.clear();
  if (path == nullptr) return Status::kInvalidArgument;
  std::FILE* f = std::fopen(path, "rb");
  if (f == nullptr) return Status::kIoError;
  Status status = Status::kOk;
  try {
    // Read in growing chunks until EOF: works for pipes and files whose size changes.
    std::size_t used = 0;
    std::size_t chunk = 1 << 16;
    for (;;) {
      out.resize(used + chunk);
      const std::size_t got = std::fread(out.data() + used, 1, chunk, f);
      used += got;
      if (got < chunk) break;
      if (chunk < (std::size_t{1} << 26)) chunk *= 2;
    }
    out.resize(used);
    if (std::ferror(f)) status = Status::kIoError;
  } catch (const std::bad_alloc&) {
    status = Status::kOutOfMemory;
  }
  std::fclose(f);
  if (status != Status::kOk) out = Bytes();
  return status;
}

}  // namespace

Status read_file(const char* path, std::vector<std::byte>& out) noexcept {
  return read_whole_file(path, out);
}

namespace detail {
Status read_file_large(const char* path, LargeVector<std::byte>& out) noexcept {
  return read_whole_file(path, out);
}
}  // namespace detail

void write_file_atomic(const std::string& path, const void* data, std::size_t size) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  // A random suffix keeps concurrent writers of the same target apart.
  std::random_device device;
  const fs::path temp = target.string() + ".tmp-" + std::to_string(device());
  auto fail = [&](const std::string& reason) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw FileWriteError(path + ": " + reason);
  };
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) fail(std::string("cannot create temporary file: ") + std::strerror(errno));
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.flush();
    if (!out) fail(std::string("write failed: ") + std::strerror(errno));
    out.close();
    if (!out) fail(std::string("close failed: ") + std::strerror(errno));
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) fail("cannot rename the temporary file into place: " + ec.message());
}

}  // namespace urbanpvs::runtime
