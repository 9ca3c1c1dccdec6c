// SPDX-License-Identifier: MIT
#pragma once

// Encoding of one cell's PVS in the pvs section (layout in FORMAT.md, "5 — pvs"):
//   delta list: kind 0, varint count, count gaps (first id, then id - previous - 1)
//   bitset:     kind 1, varint count, varint first byte, varint byte count, bytes
//   diff:       kind 2, varint count, varint zigzag(ref - cell), varint #removed, varint #added,
//               removed positions in ref's list (gaps), added ids (gaps)
// The gaps are varints in the plain layout (2.0, 2.1) and exp-Golomb codes in the coded one
// (2.2), whose kind byte also holds the codes' orders. Diffs exploit the coherence of
// neighbouring cells (they share ~90% of their PVS); chains of diffs are bounded by
// format::kMaxDiffChain so a lookup stays a few linear passes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/Status.hpp"
#include "urbanpvs/runtime/Types.hpp"

namespace urbanpvs::runtime::detail {

/// The pvs section as the reader sees it (all ranges already checked against the buffer).
struct PvsSection {
  /// Plain: cell_count + 1 little-endian u32 starts. Coded: the block index (cell_start).
  const unsigned char* offsets = nullptr;
  const unsigned char* payload = nullptr;
  std::size_t payload_size = 0;
  std::uint32_t cell_count = 0;
  std::uint32_t object_count = 0;
  bool coded = false;             ///< the 2.2 layout (format::kFeatureCodedPvs)
  std::uint32_t block_shift = 0;  ///< coded: 2^block_shift cells per index block
  /// Coded: the cells' derived neighbours (cell_count entries), the targets of a diff's
  /// neighbour-slot reference.
  const std::array<std::uint32_t, 3>* neighbours = nullptr;
};

/// Reference codes below this name a neighbour slot of the cell (coded layout); code c >= it is
/// the zigzag difference c - kNeighbourSlots.
inline constexpr std::uint32_t kNeighbourSlots = 3;

/// Most cells per block of the coded index (2^4): 16 cells share one u32 start and store 15
/// u16 offsets from it, 2.1 bytes per cell instead of 4.
inline constexpr std::uint32_t kMaxBlockShift = 4;

/// Bytes of the coded block index of `cells` cells in blocks of 2^shift.
std::uint64_t block_index_size(std::uint32_t cells, std::uint32_t shift) noexcept;

/// Start of `cell`'s payload (cell <= cell_count; cell_count gives the payload size), unchecked
/// against the payload size.
std::uint64_t cell_start(const PvsSection& section, std::uint32_t cell) noexcept;

/// Starts loading the index entry that cell_start(section, cell) reads (cell < cell_count).
void prefetch_pvs_start(const PvsSection& section, std::uint32_t cell) noexcept;

/// The byte range of `cell`'s payload; false when the cell or the index is out of range.
bool payload_range(const PvsSection& section, std::uint32_t cell, std::uint32_t& begin,
                   std::uint32_t& end) noexcept;

/// The parsed first fields of a cell payload.
/// (No default member initializers here and below: a Chain is built on every lookup, and
/// zero-filling its arrays cost more than the decode of a small PVS.)
struct PayloadHeader {
  format::PvsKind kind;
  bool coded;           ///< gaps are exp-Golomb codes (section.coded)
  std::uint8_t orders;  ///< coded: the kind byte's bits 2..7 (list: k; diff: kr | ka << 3)
  /// Size of the cell's PVS. A coded diff does not store it (it is its reference's count -
  /// removed + added): 0 here, filled in by resolve_chain.
  std::uint32_t count;
  const unsigned char* body;      ///< first byte after the count
  const unsigned char* end;       ///< end of the payload
  const unsigned char* blob_end;  ///< end of all payloads: bytes a bit reader may look at
};

/// The parsed fields of a diff payload after its header.
struct DiffHeader {
  std::uint32_t reference;
  std::uint32_t removed;
  std::uint32_t added;
  bool coded;  ///< exp-Golomb codes of orders removed_order and added_order
  std::uint8_t removed_order;
  std::uint8_t added_order;
  const unsigned char* lists;  ///< removed positions, then added ids (one bit stream if coded)
  const unsigned char* end;
  const unsigned char* blob_end;
};

/// Reads the header of `cell`'s payload; false when the offsets or the header are invalid.
bool read_payload_header(const PvsSection& section, std::uint32_t cell,
                         PayloadHeader& header) noexcept;

/// Reads the diff fields of a kDiff payload of `cell`; false when they are invalid (reference
/// out of range, the cell itself, or an empty neighbour slot).
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
/// kMaxDiffChain diff steps away (which also rules out cycles). Fills in the derived counts of
/// coded diffs (false when one would be negative or above the object count).
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
/// `count` entries below object_count, without building it: one pass over the diff's codes and
/// one over the reference. `scratch` holds the removed positions (false when they need more than
/// `scratch_size` slots; reference_count slots always do). Exactly when merge_decoded succeeds
/// with `count` entries, strictly increasing and in range.
bool check_diff(const DiffHeader& diff, std::uint32_t count, const std::uint32_t* reference,
                std::size_t reference_count, std::uint32_t object_count, std::uint32_t* scratch,
                std::size_t scratch_size) noexcept;

/// Whether `object` is in the PVS of `cell`, by scanning the encoded lists (no buffer).
bool cell_contains(const PvsSection& section, std::uint32_t cell, std::uint32_t object) noexcept;

/// Bytes of the payload of the encodings below; exact. `coded`: the 2.2 layout (exp-Golomb
/// gaps, orders chosen per list), else the plain one.
void encode_delta_list(const std::vector<std::uint32_t>& ids, bool coded,
                       std::vector<unsigned char>& out);
void encode_bitset(const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out);
/// The smaller of the two full encodings (delta list on ties).
void encode_full(const std::vector<std::uint32_t>& ids, bool coded,
                 std::vector<unsigned char>& out);
/// `ids` as removals/additions against `reference_ids` (the PVS of cell `reference`). Coded:
/// `neighbours` are the cell's derived neighbours (a reference among them takes its slot), and
/// the diff has no count.
void encode_diff(std::uint32_t cell, std::uint32_t reference,
                 const std::array<std::uint32_t, 3>& neighbours,
                 const std::vector<std::uint32_t>& reference_ids,
                 const std::vector<std::uint32_t>& ids, bool coded,
                 std::vector<unsigned char>& out);

/// zigzag of the wrapped difference reference - cell: small for nearby indices, a bijection on
/// 32-bit values so every reference is expressible.
std::uint32_t encode_reference(std::uint32_t cell, std::uint32_t reference) noexcept;
std::uint32_t decode_reference(std::uint32_t cell, std::uint32_t zigzag) noexcept;

/// Whether a coded diff of `cell` can name `reference` (every reference but the few whose
/// zigzag code would not fit a u32 after the neighbour slots).
bool coded_reference_fits(std::uint32_t cell, std::uint32_t reference) noexcept;

}  // namespace urbanpvs::runtime::detail
