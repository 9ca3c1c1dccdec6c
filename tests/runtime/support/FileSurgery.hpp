// SPDX-License-Identifier: MIT
#pragma once

// Byte-level editing of .pvs files for rejection tests, written from FORMAT.md (not from the
// library's own container code), so the tests also check the implementation against the spec.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace urbanpvs::test {

using Bytes = std::vector<std::byte>;

std::uint16_t get_u16(const Bytes& b, std::size_t at);
std::uint32_t get_u32(const Bytes& b, std::size_t at);
std::uint64_t get_u64(const Bytes& b, std::size_t at);
void put_u16(Bytes& b, std::size_t at, std::uint16_t v);
void put_u32(Bytes& b, std::size_t at, std::uint32_t v);
void put_u64(Bytes& b, std::size_t at, std::uint64_t v);

struct SectionEntry {
  std::size_t table_at;  ///< byte offset of the table entry
  std::uint32_t id;
  std::uint64_t offset, length;
};

/// The section table as written in the header.
std::vector<SectionEntry> section_table(const Bytes& file);
/// The entry of section `id` (aborts the test binary when absent).
SectionEntry section(const Bytes& file, std::uint32_t id);

/// Recomputes every section CRC and the header CRC, so a structural edit reaches the checks
/// behind the checksums.
void reseal(Bytes& file);

/// Replaces the bytes of section `id` (adjusting offsets, lengths, file size) and reseals.
void replace_section(Bytes& file, std::uint32_t id, const Bytes& content);

/// Reads a file into bytes.
Bytes read_bytes(const char* path);

}  // namespace urbanpvs::test
