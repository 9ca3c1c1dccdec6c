// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/BakeFingerprint.hpp"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::preprocess {

void Fnv1a64::add_bytes(const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint64_t h = state_;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  state_ = h;
}

void Fnv1a64::add_u64(std::uint64_t value) {
  std::array<unsigned char, 8> le{};
  for (std::size_t i = 0; i < 8; ++i) le[i] = static_cast<unsigned char>(value >> (8 * i));
  add_bytes(le.data(), le.size());
}

void Fnv1a64::add_string(std::string_view text) {
  add_u64(text.size());
  add_bytes(text.data(), text.size());
}

std::uint64_t hash_input_files(const std::vector<std::string>& paths) {
  Fnv1a64 h;
  std::vector<unsigned char> buffer(1 << 20);
  for (const std::string& path : paths) {
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                               &std::fclose);
    auto unreadable = [&] {
      return geometry::InputError(geometry::InputProblem::Unreadable, path, "",
                                  path + ": cannot read: " + std::strerror(errno));
    };
    if (!file) throw unreadable();
    // The length goes first, yet is only known at the end: hash the bytes separately.
    Fnv1a64 bytes;
    std::uint64_t size = 0;
    for (;;) {
      const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), file.get());
      bytes.add_bytes(buffer.data(), n);
      size += n;
      if (n < buffer.size()) {
        if (std::ferror(file.get())) throw unreadable();
        break;
      }
    }
    h.add_u64(size);
    h.add_u64(bytes.value());
  }
  return h.value();
}

std::string hex64(std::uint64_t value) {
  char text[19];
  std::snprintf(text, sizeof text, "0x%016llx", static_cast<unsigned long long>(value));
  return text;
}

std::uint64_t bake_fingerprint(std::uint64_t input_hash,
                               const std::vector<std::pair<std::string, std::string>>& settings,
                               std::size_t cells, std::size_t objects) {
  Fnv1a64 h;
  // The version of what a cell's PVS is, for the same settings: 2 tests objects by their
  // outline (ObjectCulling), so a journal of version 1 must not be resumed into it.
  h.add_string("urbanpvs bake fingerprint 2");
  h.add_u64(input_hash);
  h.add_u64(settings.size());
  for (const auto& [key, value] : settings) {
    h.add_string(key);
    h.add_string(value);
  }
  h.add_u64(cells);
  h.add_u64(objects);
  return h.value();
}

}  // namespace urbanpvs::preprocess
