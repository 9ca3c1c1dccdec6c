// SPDX-License-Identifier: MIT
#include "Container.hpp"

#include <cstring>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "urbanpvs/runtime/Crc32c.hpp"
#include "urbanpvs/runtime/Format.hpp"

namespace urbanpvs::runtime::detail {
namespace {

static_assert(format::kFixedHeaderSize == 8 + 2 + 2 + 4 + 8 + 4 + 4 + 4 + 4, "FORMAT.md header");
static_assert(format::kSectionEntrySize == 4 + 4 + 8 + 8, "FORMAT.md section table entry");
static_assert(format::kHeaderCrcOffset == 32, "FORMAT.md header");

Status fail(LoadError& error, Status status, const char* detail, std::uint32_t section = 0) {
  error = {status, section, detail};
  return status;
}

/// CRC32C of the header with its own checksum field taken as zero.
std::uint32_t header_crc(const unsigned char* data, std::size_t header_size) noexcept {
  static constexpr unsigned char kZero[4] = {0, 0, 0, 0};
  std::uint32_t crc = crc32c(data, format::kHeaderCrcOffset);
  crc = crc32c(kZero, 4, crc);
  return crc32c(data + format::kHeaderCrcOffset + 4, header_size - format::kHeaderCrcOffset - 4,
                crc);
}

}  // namespace

Status read_container(const unsigned char* data, std::size_t size, bool verify_checksums,
                      ContainerInfo& info, LoadError& error) {
  using namespace format;
  // Magic and major version come first: a different major may lay out everything else
  // differently, so nothing after the version is trusted before the version is known.
  if (size < sizeof kMagic) {
    return (size == 0 || std::memcmp(data, kMagic, size) == 0)
               ? fail(error, Status::kTruncated, "file shorter than the magic")
               : fail(error, Status::kBadMagic, "not a .pvs file (bad magic)");
  }
  if (std::memcmp(data, kMagic, sizeof kMagic) != 0) {
    return fail(error, Status::kBadMagic, "not a .pvs file (bad magic)");
  }
  if (size < 10) return fail(error, Status::kTruncated, "file ends inside the header");
  info.major = load_u16(data + 8);
  if (info.major < format::kOldestMajorVersion || info.major > kMajorVersion) {
    return fail(error, Status::kUnsupportedVersion,
                info.major > kMajorVersion ? "newer major version than this reader supports"
                                           : "older major version than this reader supports");
  }
  if (size < kFixedHeaderSize)
    return fail(error, Status::kTruncated, "file ends inside the header");
  info.minor = load_u16(data + 10);
  const std::uint32_t header_size = load_u32(data + 12);
  const std::uint64_t file_size = load_u64(data + 16);
  const std::uint32_t section_count = load_u32(data + 24);
  info.required_features = load_u32(data + 28);
  const std::uint32_t stored_crc = load_u32(data + kHeaderCrcOffset);
  const std::uint32_t reserved = load_u32(data + 36);
  if (header_size < kFixedHeaderSize) {
    return fail(error, Status::kMalformedHeader, "header size smaller than the fixed header");
  }
  if (header_size > size) return fail(error, Status::kTruncated, "file ends inside the header");
  if (verify_checksums && header_crc(data, header_size) != stored_crc) {
    return fail(error, Status::kHeaderChecksumMismatch, "header checksum mismatch");
  }
  if (file_size > size) return fail(error, Status::kTruncated, "file shorter than its header says");
  if (file_size < size) {
    return fail(error, Status::kTrailingBytes, "bytes after the end of the file");
  }
  if (reserved != 0) return fail(error, Status::kMalformedHeader, "reserved header field not zero");
  const std::uint64_t table_end =
      kFixedHeaderSize + std::uint64_t{section_count} * kSectionEntrySize;
  // A newer minor version may append header fields after the table; ours may not.
  if (table_end > header_size ||
      (info.minor <= format::latest_minor(info.major) && table_end != header_size)) {
    return fail(error, Status::kMalformedHeader, "header size does not match the section count");
  }
  // The coded PVS is a 2.x feature: a 1.x file that asks for it is not one this reader knows.
  const std::uint32_t known = info.major == 1 ? 0 : kKnownRequiredFeatures;
  if ((info.required_features & ~known) != 0) {
    return fail(error, Status::kUnsupportedFeature,
                "file requires features this reader does not implement (newer minor version)");
  }

  info.sections.clear();
  info.sections.reserve(section_count);  // bounded: count * 24 <= header_size <= size
  std::uint64_t expected_offset = header_size;
  for (std::uint32_t i = 0; i < section_count; ++i) {
    const unsigned char* entry = data + kFixedHeaderSize + std::size_t{i} * kSectionEntrySize;
    SectionInfo s{load_u32(entry), load_u32(entry + 4), load_u64(entry + 8), load_u64(entry + 16)};
    if (!info.sections.empty() && s.id <= info.sections.back().id) {
      return fail(error, Status::kMalformedHeader, "section ids not strictly increasing", s.id);
    }
    // Sections tile [header_size, file_size) exactly: no gaps means no byte escapes the
    // checksums, no overlap means no byte has two meanings.
    if (s.offset != expected_offset || s.length > file_size - s.offset) {
      return fail(error, Status::kMalformedHeader, "section outside the file or not contiguous",
                  s.id);
    }
    expected_offset = s.offset + s.length;
    info.sections.push_back(s);
  }
  if (expected_offset != file_size) {
    return fail(error, Status::kMalformedHeader, "sections do not reach the end of the file");
  }
  if (verify_checksums) {
    for (const SectionInfo& s : info.sections) {
      if (crc32c(data + s.offset, static_cast<std::size_t>(s.length)) != s.crc32c) {
        return fail(error, Status::kSectionChecksumMismatch, "section checksum mismatch", s.id);
      }
    }
  }
  error = {};
  return Status::kOk;
}

std::vector<std::byte> write_container(const std::vector<SectionBytes>& sections,
                                       std::uint16_t major, std::uint16_t minor,
                                       std::uint32_t required_features) {
  using namespace format;
  const std::uint32_t header_size =
      kFixedHeaderSize + static_cast<std::uint32_t>(sections.size()) * kSectionEntrySize;
  std::uint64_t file_size = header_size;
  for (const auto& s : sections) file_size += s.second.size();

  ByteWriter w;
  w.raw(kMagic, sizeof kMagic);
  w.u16(major);
  w.u16(minor);
  w.u32(header_size);
  w.u64(file_size);
  w.u32(static_cast<std::uint32_t>(sections.size()));
  w.u32(required_features);
  w.u32(0);  // header crc, patched below
  w.u32(0);  // reserved
  std::uint64_t offset = header_size;
  for (const auto& [id, bytes] : sections) {
    w.u32(id);
    w.u32(crc32c(bytes.data(), bytes.size()));
    w.u64(offset);
    w.u64(bytes.size());
    offset += bytes.size();
  }
  w.patch_u32(kHeaderCrcOffset, header_crc(w.bytes().data(), header_size));
  for (const auto& s : sections) w.raw(s.second.data(), s.second.size());

  std::vector<std::byte> out(w.size());
  std::memcpy(out.data(), w.bytes().data(), w.size());
  return out;
}

}  // namespace urbanpvs::runtime::detail
