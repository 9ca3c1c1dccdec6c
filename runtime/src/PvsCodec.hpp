// SPDX-License-Identifier: MIT
#pragma once

// Encoding of one cell's PVS in the pvs section (layout in FORMAT.md, "pvs section"):
//   delta list: kind 0, varint count, count varint gaps (first id, then id - previous - 1)
//   bitset:     kind 1, varint count, varint first byte, varint byte count, bytes
//   diff:       kind 2, varint count, varint zigzag(ref - cell), varint #removed, varint #added,
//               removed positions in ref's list (gaps), added ids (gaps)
// Diffs exploit the coherence of neighbouring cells (they share ~90% of their PVS); chains of
// diffs are bounded by format::kMaxDiffChain so a lookup stays a few linear passes.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/Status.hpp"

namespace urbanpvs::runtime::detail {

/// The pvs section as the reader sees it (all ranges already checked against the buffer).
struct PvsSection {
  const unsigned char* offsets = nullptr;  ///< cell_count + 1 little-endian u32
  const unsigned char* payload = nullptr;
  std::size_t payload_size = 0;
  std::uint32_t cell_count = 0;
  std::uint32_t object_count = 0;
};

/// The parsed first fields of a cell payload.
/// (No default member initializers here and below: a Chain is built on every lookup, and
/// zero-filling its arrays cost more than the decode of a small PVS.)
struct PayloadHeader {
  format::PvsKind kind;
  std::uint32_t count;        ///< size of the cell's PVS
  const unsigned char* body;  ///< first byte after the count
  const unsigned char* end;   ///< end of the payload
};

/// The parsed fields of a diff payload after its header.
struct DiffHeader {
  std::uint32_t reference;
  std::uint32_t removed;
  std::uint32_t added;
  const unsigned char* lists;  ///< removed positions, then added ids
  const unsigned char* end;
};

/// Reads the header of `cell`'s payload; false when the offsets or the header are invalid.
bool read_payload_header(const PvsSection& section, std::uint32_t cell,
                         PayloadHeader& header) noexcept;

/// Reads the diff fields of a kDiff payload of `cell`; false when they are invalid (reference
/// out of range or the cell itself).
bool read_diff_header(const PvsSection& section, std::uint32_t cell, const PayloadHeader& header,
                      DiffHeader& diff) noexcept;

/// The cells from `cell` down to its full base, with their headers.
struct Chain {
  std::uint32_t cells[format::kMaxDiffChain + 1];
  PayloadHeader headers[format::kMaxDiffChain + 1];
  DiffHeader diffs[format::kMaxDiffChain + 1];  ///< valid for the kDiff entries
  std::uint32_t diff_steps;  ///< entries [0, diff_steps) are diffs, entry diff_steps is full
};

/// Follows the references of `cell`; false when a header is invalid or the base is more than
/// kMaxDiffChain diff steps away (which also rules out cycles).
bool resolve_chain(const PvsSection& section, std::uint32_t cell, Chain& chain) noexcept;

/// Decodes the PVS of `cell` into `buffer`. `half` slots are one working list (>= the largest
/// PVS of the file); chains of two or more diffs also use [half, 2 * half). Checks every read
/// and write, so it fails (kMalformedSection) instead of overrunning on inconsistent data.
Status decode_cell(const PvsSection& section, std::uint32_t cell, std::uint32_t* buffer,
                   std::size_t half, std::size_t& count) noexcept;

/// One diff step from a decoded reference list reference[0, count) into out[0, written), as
/// decode_cell does (checked reads and writes; the result is not checked ascending).
bool merge_decoded(const DiffHeader& diff, const std::uint32_t* reference, std::size_t count,
                   std::uint32_t* out, std::size_t capacity, std::size_t& written) noexcept;

/// Whether a diff of declared size `count` against the decoded, strictly increasing list
/// reference[0, reference_count) (entries < object_count) gives a strictly increasing list of
/// `count` entries below object_count, without building it: O((removed + added) log n). Exactly
/// when merge_decoded succeeds with `count` entries, strictly increasing and in range.
bool check_diff(const DiffHeader& diff, std::uint32_t count, const std::uint32_t* reference,
                std::size_t reference_count, std::uint32_t object_count) noexcept;

/// Whether `object` is in the PVS of `cell`, by scanning the encoded lists (no buffer).
bool cell_contains(const PvsSection& section, std::uint32_t cell, std::uint32_t object) noexcept;

/// Bytes of the payload of the encodings below; exact.
void encode_delta_list(const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out);
void encode_bitset(const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out);
/// The smaller of the two full encodings (delta list on ties).
void encode_full(const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out);
/// `ids` as removals/additions against `reference_ids` (the PVS of cell `reference`).
void encode_diff(std::uint32_t cell, std::uint32_t reference,
                 const std::vector<std::uint32_t>& reference_ids,
                 const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out);

/// zigzag of the wrapped difference reference - cell: small for nearby indices, a bijection on
/// 32-bit values so every reference is expressible.
std::uint32_t encode_reference(std::uint32_t cell, std::uint32_t reference) noexcept;
std::uint32_t decode_reference(std::uint32_t cell, std::uint32_t zigzag) noexcept;

}  // namespace urbanpvs::runtime::detail
