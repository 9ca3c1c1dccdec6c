// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Status codes of the urbanpvs runtime. The runtime never throws: every fallible call returns one
/// of these. The numeric values are part of the C API (urbanpvs.h) and never change meaning.

namespace urbanpvs::runtime {

enum class Status : int {
  kOk = 0,
  /// The buffer does not start with the .pvs magic bytes: not a PVS file at all.
  kBadMagic = 1,
  /// The file's major version is not the one this reader implements (newer or older).
  kUnsupportedVersion = 2,
  /// Same major version, but the file sets a required-feature bit this reader does not know
  /// (how a newer minor version that older readers cannot read safely marks itself).
  kUnsupportedFeature = 3,
  /// The buffer is shorter than the header or the file size recorded in the header.
  kTruncated = 4,
  /// The buffer is longer than the file size recorded in the header.
  kTrailingBytes = 5,
  /// The header (fixed fields + section table) does not match its CRC32C.
  kHeaderChecksumMismatch = 6,
  /// A section's bytes do not match the CRC32C in the section table (see LoadError::section_id).
  kSectionChecksumMismatch = 7,
  /// Header fields are inconsistent: header size, section count, overlapping/gapped sections,
  /// duplicate section ids.
  kMalformedHeader = 8,
  /// A section every reader needs (metadata, objects, cells, grid, pvs) is absent.
  kMissingSection = 9,
  /// A section's content fails validation (counts, offsets, encodings, indices, UTF-8 ...).
  kMalformedSection = 10,
  /// A cell or object index passed by the caller is not below cell_count()/object_count().
  kOutOfRange = 11,
  /// A caller-provided buffer is smaller than the documented minimum.
  kBufferTooSmall = 12,
  /// An allocation failed (only load, PvsDecoder and read_file allocate).
  kOutOfMemory = 13,
  /// A file could not be opened or read (read_file).
  kIoError = 14,
  /// A geodetic conversion was asked of a file whose input was not geographic.
  kNotGeographic = 15,
  /// A null pointer or otherwise invalid argument (C API).
  kInvalidArgument = 16,
  /// pvs_span() on a file opened without LoadOptions::expand_pvs.
  kNotExpanded = 17,
};

/// A short, static, human-readable English description of `status` (never null).
const char* status_message(Status status) noexcept;

}  // namespace urbanpvs::runtime
