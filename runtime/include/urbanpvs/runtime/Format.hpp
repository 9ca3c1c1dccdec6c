// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Constants of the .pvs container format (see runtime/FORMAT.md for the byte layout). They are
/// public so tools and tests can name sections and check versions; the layout itself is only
/// ever read through PvsFile.

#include <cstdint>

namespace urbanpvs::runtime::format {

/// "\x89UPVS\r\n\x1a": a non-ASCII first byte and a CR LF pair catch text-mode transfers early,
/// like PNG's signature.
inline constexpr unsigned char kMagic[8] = {0x89, 'U', 'P', 'V', 'S', '\r', '\n', 0x1a};

/// The version this library writes by default. It reads every major version from
/// kOldestMajorVersion to kMajorVersion, each with any minor version, unless the file sets
/// required-feature bits the reader does not know (kKnownRequiredFeatures).
/// 1.0: cells as float64 records, a stored point-location grid. 2.0: cells as an indexed mesh of
/// quantized vertices, the grid built at load. 2.1: adds the optional payloads section; the
/// writer marks a file 2.1 only when it has one, so other files stay 2.0 byte for byte. 2.2: the
/// coded PVS (kFeatureCodedPvs): exp-Golomb gaps and a block index of 16-bit offsets.
inline constexpr std::uint16_t kMajorVersion = 2;
inline constexpr std::uint16_t kMinorVersion = 2;
inline constexpr std::uint16_t kOldestMajorVersion = 1;

/// The newest minor version this reader knows of `major` (1.0 and 2.2 so far). Bytes appended
/// to known structures are tolerated only in files of a newer minor version.
constexpr std::uint16_t latest_minor(std::uint16_t major) noexcept {
  return major == 1 ? 0 : kMinorVersion;
}

/// Required-feature bit 0 (format 2.2): the pvs section is the coded layout (FORMAT.md, "5 — pvs,
/// coded"). A 2.0/2.1 reader would misread it, so it must refuse the file instead.
inline constexpr std::uint32_t kFeatureCodedPvs = 1u << 0;

/// Required-feature bits understood by this reader. Versions 1.0, 2.0 and 2.1 define none. A
/// later minor version that changes the meaning of existing data (so that an older reader would
/// answer wrongly) must set a new bit here; one that only appends optional data must not.
inline constexpr std::uint32_t kKnownRequiredFeatures = kFeatureCodedPvs;

/// Fixed part of the header, before the section table.
inline constexpr std::uint32_t kFixedHeaderSize = 40;
/// One section table entry: id u32, crc32c u32, offset u64, length u64.
inline constexpr std::uint32_t kSectionEntrySize = 24;
/// Byte offset of the header CRC inside the fixed header (zeroed while computing it).
inline constexpr std::uint32_t kHeaderCrcOffset = 32;

/// Section identifiers. Unknown ids are skipped by readers (still checksummed), so later minor
/// versions can add optional sections.
enum class SectionId : std::uint32_t {
  kMetadata = 1,
  kObjects = 2,
  kCells = 3,
  kGrid = 4,  ///< 1.x only; 2.x builds the grid from the cells
  kPvs = 5,
  kPayloads = 6,  ///< 2.1, optional: a user value per object (a mesh or tile key)
};

/// Short lower-case name of a section id ("metadata", "objects", ...; "unknown" otherwise).
const char* section_name(std::uint32_t id) noexcept;

/// Cell PVS encodings (first byte of a cell's payload in the pvs section; its two low bits in
/// the coded layout, whose other bits hold the exp-Golomb orders).
enum class PvsKind : std::uint8_t {
  kDeltaList = 0,  ///< sorted ids as gaps (varints; exp-Golomb codes when coded)
  kBitset = 1,     ///< bit window over the object indices
  kDiff = 2,       ///< removals (positions) and additions (ids) against a reference cell
};

/// Longest chain of kDiff cells a reader follows before it must reach a full cell. Bounds the
/// work (and the stack) of a random-access lookup.
inline constexpr std::uint32_t kMaxDiffChain = 4;

/// Width of the bounding boxes in the objects section.
inline constexpr std::uint8_t kBboxFloat32 = 4;
inline constexpr std::uint8_t kBboxFloat64 = 8;

/// Fixed record size of the 1.x cells section.
inline constexpr std::uint32_t kCellRecordSize = 76;  // 8 f64 + 3 u32

}  // namespace urbanpvs::runtime::format
