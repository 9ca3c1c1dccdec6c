// SPDX-License-Identifier: MIT
#include "FileSurgery.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "urbanpvs/runtime/Crc32c.hpp"

namespace urbanpvs::test {
namespace {

constexpr std::size_t kFixedHeader = 40, kEntry = 24, kCrcAt = 32;

}  // namespace

std::uint16_t get_u16(const Bytes& b, std::size_t at) {
  return static_cast<std::uint16_t>(std::to_integer<unsigned>(b[at]) |
                                    (std::to_integer<unsigned>(b[at + 1]) << 8));
}
std::uint32_t get_u32(const Bytes& b, std::size_t at) {
  return get_u16(b, at) | (std::uint32_t{get_u16(b, at + 2)} << 16);
}
std::uint64_t get_u64(const Bytes& b, std::size_t at) {
  return get_u32(b, at) | (std::uint64_t{get_u32(b, at + 4)} << 32);
}
void put_u16(Bytes& b, std::size_t at, std::uint16_t v) {
  for (int i = 0; i < 2; ++i) b[at + i] = static_cast<std::byte>(v >> (8 * i));
}
void put_u32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::byte>(v >> (8 * i));
}
void put_u64(Bytes& b, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) b[at + i] = static_cast<std::byte>(v >> (8 * i));
}

std::vector<SectionEntry> section_table(const Bytes& file) {
  std::vector<SectionEntry> table;
  const std::uint32_t count = get_u32(file, 24);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::size_t at = kFixedHeader + kEntry * std::size_t{i};
    if (at + kEntry > file.size()) break;  // a deliberately oversized count
    table.push_back({at, get_u32(file, at), get_u64(file, at + 8), get_u64(file, at + 16)});
  }
  return table;
}

SectionEntry section(const Bytes& file, std::uint32_t id) {
  for (const SectionEntry& e : section_table(file)) {
    if (e.id == id) return e;
  }
  std::fprintf(stderr, "file_surgery: no section %u\n", id);
  std::abort();
}

void reseal(Bytes& file) {
  for (const SectionEntry& e : section_table(file)) {
    if (e.offset > file.size() || e.length > file.size() - e.offset) continue;  // broken on purpose
    put_u32(file, e.table_at + 4, runtime::crc32c(file.data() + e.offset, e.length));
  }
  const std::uint32_t header_size = get_u32(file, 12);
  if (header_size > file.size() || header_size < kFixedHeader) return;
  put_u32(file, kCrcAt, 0);
  put_u32(file, kCrcAt, runtime::crc32c(file.data(), header_size));
}

void replace_section(Bytes& file, std::uint32_t id, const Bytes& content) {
  const SectionEntry target = section(file, id);
  Bytes out(file.begin(), file.begin() + static_cast<long>(target.offset));
  out.insert(out.end(), content.begin(), content.end());
  out.insert(out.end(), file.begin() + static_cast<long>(target.offset + target.length),
             file.end());
  const std::int64_t delta =
      static_cast<std::int64_t>(content.size()) - static_cast<std::int64_t>(target.length);
  for (const SectionEntry& e : section_table(out)) {
    if (e.id == id) put_u64(out, e.table_at + 16, content.size());
    if (e.offset > target.offset) put_u64(out, e.table_at + 8, e.offset + delta);
  }
  put_u64(out, 16, out.size());
  reseal(out);
  file = std::move(out);
}

Bytes read_bytes(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Bytes bytes(chars.size());
  for (std::size_t i = 0; i < chars.size(); ++i) bytes[i] = static_cast<std::byte>(chars[i]);
  return bytes;
}

}  // namespace urbanpvs::test
