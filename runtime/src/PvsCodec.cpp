// SPDX-License-Identifier: MIT
#include "PvsCodec.hpp"

#include <algorithm>

#include "Bits.hpp"
#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "ExpGolomb.hpp"

namespace urbanpvs::runtime::detail {
namespace {

using format::PvsKind;

/// "No further element" in the merge streams (above every 32-bit value).
constexpr std::uint64_t kEnd = UINT64_MAX;

/// A strictly increasing list of a diff stored as gaps (first value, then value - previous - 1):
/// varints in the plain layout, exp-Golomb codes of one order in the coded one. Only the rare
/// events of a merge go through it, so one class with a branch serves both.
class GapStream {
 public:
  GapStream() noexcept = default;
  /// `count` varints in [p, end); `last`: the stream must end after them.
  GapStream(const unsigned char* p, const unsigned char* end, std::uint32_t count,
            bool last) noexcept
      : p_(p), end_(end), last_(last), left_(count) {}
  /// `count` codes of order k from `bits`; `last`: the stream must end after them.
  GapStream(const BitReader& bits, unsigned k, std::uint32_t count, bool last) noexcept
      : bits_(bits), k_(k), coded_(true), last_(last), left_(count) {}

  /// Next value, or kEnd once `count` values were read (then a `last` stream must be exactly at
  /// its end). False on malformed data.
  bool next(std::uint64_t& value) noexcept {
    if (left_ == 0) {
      value = kEnd;
      return !last_ || (coded_ ? bits_.at_padded_end() : p_ == end_);
    }
    std::uint64_t gap;
    if (coded_) {
      if (!bits_.code(k_, gap)) return false;
    } else {
      std::uint32_t g;
      if (!read_varint(p_, end_, g)) return false;
      gap = g;
    }
    value = base_ + gap;
    if (value > UINT32_MAX) return false;
    base_ = value + 1;
    --left_;
    return true;
  }

  /// The `count` values that follow this stream's once they are all read (order k if coded).
  GapStream following(unsigned k, std::uint32_t count, bool last) const noexcept {
    return coded_ ? GapStream(bits_, k, count, last) : GapStream(p_, end_, count, last);
  }

 private:
  const unsigned char* p_ = nullptr;
  const unsigned char* end_ = nullptr;
  BitReader bits_{nullptr, 0};
  unsigned k_ = 0;
  bool coded_ = false;
  bool last_ = false;
  std::uint32_t left_ = 0;
  std::uint64_t base_ = 0;
};

/// The removals of a diff; the additions are its following() stream once they are read.
GapStream diff_removals(const DiffHeader& d) noexcept {
  if (d.coded) {
    const BitReader bits(d.lists, static_cast<std::size_t>(d.end - d.lists),
                         static_cast<std::size_t>(d.blob_end - d.lists));
    return GapStream(bits, d.removed_order, d.removed, false);
  }
  return GapStream(d.lists, d.end, d.removed, false);
}

/// The additions of a diff once `removals` (diff_removals) are read.
GapStream diff_additions(const DiffHeader& d, const GapStream& removals) noexcept {
  return removals.following(d.added_order, d.added, true);
}

/// The removals and the additions of a diff, each as a stream, for reading both at once (the
/// removals are skipped to find the additions); false when the removals run past the payload.
bool open_diff_lists(const DiffHeader& d, GapStream& removals, GapStream& additions) noexcept {
  removals = diff_removals(d);
  GapStream skipped = removals;
  for (std::uint64_t q;;) {
    if (!skipped.next(q)) return false;
    if (q == kEnd) break;
  }
  additions = diff_additions(d, skipped);
  return true;
}

/// read_varint for streams of mostly one- and two-byte values (PVS gaps): those are decoded
/// without a data-dependent branch — whether a gap takes one or two bytes is close to random,
/// and mispredicting it cost more than the rest of the decode. Anything else (longer, non-
/// minimal, or at the very end of the payload) goes through read_varint.
inline bool read_short_varint(const unsigned char*& p, const unsigned char* end,
                              std::uint32_t& value) noexcept {
  if (end - p < 2) return read_varint(p, end, value);
  const std::uint32_t b0 = p[0], b1 = p[1];
  const std::uint32_t two = b0 >> 7;  // 1 when a second byte follows
  const std::uint32_t unusual = two & ((b1 >> 7) | static_cast<std::uint32_t>(b1 == 0));
  if (unusual != 0) return read_varint(p, end, value);
  value = (b0 & 0x7Fu) | ((b1 << 7) & (0u - two));
  p += 1 + two;
  return true;
}

// Sources: the elements of a sorted list, one next() call per element (the caller knows the
// count), and finish() to check afterwards that the encoding held exactly that many.

/// A kDeltaList payload.
class DeltaSource {
 public:
  explicit DeltaSource(const PayloadHeader& h) noexcept : p_(h.body), end_(h.end) {}

  bool next(std::uint64_t& v) noexcept {
    std::uint32_t gap;
    if (!read_short_varint(p_, end_, gap)) return false;
    v = next_ + gap;
    next_ = v + 1;
    return true;
  }
  /// Values only grow, so checking the last one against 2^32 checks them all.
  bool finish() const noexcept { return p_ == end_ && next_ <= std::uint64_t{UINT32_MAX} + 1; }

 private:
  const unsigned char* p_;
  const unsigned char* end_;
  std::uint64_t next_ = 0;  // smallest value the next element can have
};

/// A coded kDeltaList payload: exp-Golomb gaps of order k.
class CodedListSource {
 public:
  explicit CodedListSource(const PayloadHeader& h) noexcept
      : bits_(h.body, static_cast<std::size_t>(h.end - h.body),
              static_cast<std::size_t>(h.blob_end - h.body)),
        k_(h.orders) {}

  bool next(std::uint64_t& v) noexcept {
    std::uint64_t gap;
    if (!bits_.code(k_, gap)) return false;
    v = next_ + gap;
    next_ = v + 1;
    return true;
  }
  bool finish() const noexcept {
    return bits_.at_padded_end() && next_ <= std::uint64_t{UINT32_MAX} + 1;
  }

 private:
  BitReader bits_;
  unsigned k_;
  std::uint64_t next_ = 0;
};

/// The bit window of a kBitset payload, checked canonical: non-empty, first and last byte
/// non-zero, every bit index below 2^32.
struct BitsetWindow {
  std::uint64_t first_bit = 0;
  const unsigned char* bytes = nullptr;
  std::uint32_t size = 0;
};

bool read_bitset(const PayloadHeader& h, BitsetWindow& w) noexcept {
  const unsigned char* p = h.body;
  std::uint32_t first_byte, size;
  if (!read_varint(p, h.end, first_byte) || !read_varint(p, h.end, size)) return false;
  if (size == 0 || static_cast<std::size_t>(h.end - p) != size) return false;
  if (p[0] == 0 || p[size - 1] == 0) return false;
  if ((static_cast<std::uint64_t>(first_byte) + size) * 8 > (std::uint64_t{1} << 32)) return false;
  w = {static_cast<std::uint64_t>(first_byte) * 8, p, size};
  return true;
}

/// A kBitset payload.
class BitsetSource {
 public:
  explicit BitsetSource(const PayloadHeader& h) noexcept {
    BitsetWindow w;
    if (!read_bitset(h, w)) return;  // p_ == end_: next() fails at once
    p_ = w.bytes;
    end_ = w.bytes + w.size;
    next_base_ = w.first_bit;
    valid_ = true;
  }

  bool next(std::uint64_t& v) noexcept {
    while (bits_ == 0) {
      if (p_ == end_) return false;
      bits_ = *p_++;
      base_ = next_base_;
      next_base_ += 8;
    }
    v = base_ + count_trailing_zeros(bits_);
    bits_ &= bits_ - 1;
    return true;
  }
  /// No set bit left over: the popcount was exactly the count.
  bool finish() const noexcept { return valid_ && p_ == end_ && bits_ == 0; }

 private:
  const unsigned char* p_ = nullptr;
  const unsigned char* end_ = nullptr;
  std::uint32_t bits_ = 0;
  std::uint64_t base_ = 0;
  std::uint64_t next_base_ = 0;
  bool valid_ = false;
};

/// An already decoded list (the intermediate steps of a chain).
class ArraySource {
 public:
  explicit ArraySource(const std::uint32_t* data) noexcept : p_(data) {}
  bool next(std::uint64_t& v) noexcept {
    v = *p_++;
    return true;
  }
  bool finish() const noexcept { return true; }

 private:
  const std::uint32_t* p_;
};

/// The `count` elements of `src` into out[0, written).
template <class Source>
URBANPVS_NOINLINE bool drain(Source src, std::uint32_t count, std::uint32_t* out,
                             std::size_t capacity, std::size_t& written) noexcept {
  if (count > capacity) return false;
  for (std::uint32_t i = 0; i < count; ++i) {
    std::uint64_t v;
    if (!src.next(v)) return false;
    out[i] = static_cast<std::uint32_t>(v);
  }
  written = count;
  return src.finish();
}

/// Calls f with the source of a full payload (plain list, coded list or bitset).
template <class F>
bool with_full_source(const PayloadHeader& h, F&& f) noexcept {
  if (h.kind == PvsKind::kBitset) return f(BitsetSource(h));
  if (h.coded) return f(CodedListSource(h));
  return f(DeltaSource(h));
}

bool decode_full(const PayloadHeader& h, std::uint32_t* out, std::size_t capacity,
                 std::size_t& written) noexcept {
  return with_full_source(h, [&](auto src) { return drain(src, h.count, out, capacity, written); });
}

/// The rarely touched state of a merge: the removal and addition streams. Kept out of line
/// (only reached through the cold helpers below) so that the hot loop's few variables stay in
/// registers.
struct DiffCursor {
  GapStream removals;
  GapStream additions;
  std::uint64_t next_removal;
  std::uint64_t next_addition;
};

URBANPVS_NOINLINE bool next_removal(DiffCursor& c) noexcept {
  return c.removals.next(c.next_removal);
}

/// Writes the additions below `v` to out[w...]; `limit` is the last slot they may use.
URBANPVS_NOINLINE bool emit_additions_below(DiffCursor& c, std::uint64_t v, std::uint32_t* out,
                                            std::size_t& w, std::size_t limit) noexcept {
  while (c.next_addition < v) {
    if (w >= limit) return false;
    out[w++] = static_cast<std::uint32_t>(c.next_addition);
    if (!c.additions.next(c.next_addition)) return false;
  }
  return true;
}

/// One merge pass: the `count` elements of the reference list `src`, minus the removed
/// positions, plus the added ids, into out[0, written). Single pass, straight from the
/// reference's encoding. Events (removals, additions) are rare, so the loop runs over the
/// segments between removals and the inner loop is a plain decode plus one comparison.
template <class Source>
URBANPVS_NOINLINE bool merge(Source src, std::uint32_t count, const DiffHeader& d,
                             std::uint32_t* out, std::size_t capacity,
                             std::size_t& written) noexcept {
  DiffCursor c{{}, {}, 0, 0};
  if (!open_diff_lists(d, c.removals, c.additions)) return false;
  if (!next_removal(c) || !c.additions.next(c.next_addition)) return false;
  std::size_t w = 0;
  std::uint64_t position = 0;
  for (;;) {
    const std::uint64_t removal = c.next_removal;
    if (removal != kEnd && removal >= count) return false;  // past the reference list
    const std::uint64_t stop = removal == kEnd ? count : removal;
    const std::size_t segment = static_cast<std::size_t>(stop - position);
    if (capacity - w < segment) return false;
    std::uint64_t next_addition = c.next_addition;
    for (std::size_t left = segment; left > 0; --left) {
      std::uint64_t v;
      if (!src.next(v)) return false;
      if (v > next_addition) {
        // Room for the additions and the rest of the segment.
        if (!emit_additions_below(c, v, out, w, capacity - left)) return false;
        next_addition = c.next_addition;
      }
      out[w++] = static_cast<std::uint32_t>(v);
    }
    if (removal == kEnd) break;
    std::uint64_t removed;
    if (!src.next(removed) || !next_removal(c)) return false;
    position = stop + 1;
  }
  if (!src.finish() || !emit_additions_below(c, kEnd, out, w, capacity)) return false;
  written = w;
  return true;
}

/// First step of a chain: merge straight from the full base payload.
bool merge_full(const PayloadHeader& base, const DiffHeader& d, std::uint32_t* out,
                std::size_t capacity, std::size_t& written) noexcept {
  return with_full_source(
      base, [&](auto src) { return merge(src, base.count, d, out, capacity, written); });
}

/// Number of elements below `object` in a list, and whether `object` is in it.
struct Rank {
  std::uint64_t below = 0;
  bool present = false;
};

/// rank_in_full of a delta list, plain or coded.
template <class Source>
bool rank_in_list(Source src, std::uint32_t count, std::uint32_t object, Rank& rank) noexcept {
  for (std::uint32_t i = 0; i < count; ++i) {
    std::uint64_t v;
    if (!src.next(v)) return false;
    if (v >= object) {  // sorted: stop at the first element not below `object`
      rank = {i, v == object};
      return true;
    }
  }
  rank = {count, false};
  return src.finish();
}

bool rank_in_full(const PayloadHeader& h, std::uint32_t object, Rank& rank) noexcept {
  if (h.kind == PvsKind::kDeltaList) {
    if (h.coded) return rank_in_list(CodedListSource(h), h.count, object, rank);
    return rank_in_list(DeltaSource(h), h.count, object, rank);
  }
  BitsetWindow w;
  if (!read_bitset(h, w)) return false;
  if (object < w.first_bit) {
    rank = {0, false};
    return true;
  }
  const std::uint64_t byte = (object - w.first_bit) / 8;
  if (byte >= w.size) {
    rank = {h.count, false};
    return true;
  }
  const unsigned bit = static_cast<unsigned>((object - w.first_bit) % 8);
  std::uint64_t below = 0;
  for (std::uint64_t i = 0; i < byte; ++i) below += popcount8(w.bytes[i]);
  below += popcount8(w.bytes[byte] & ((1u << bit) - 1u));
  rank = {below, ((w.bytes[byte] >> bit) & 1u) != 0};
  return true;
}

/// Carries a rank in the reference list through one diff.
bool rank_through_diff(const DiffHeader& d, std::uint32_t object, Rank& rank) noexcept {
  GapStream removals, additions;
  if (!open_diff_lists(d, removals, additions)) return false;
  std::uint64_t removed_below = 0;
  bool removed_self = false;
  for (std::uint64_t q;;) {
    if (!removals.next(q)) return false;
    if (q == kEnd) break;
    if (q < rank.below) {
      ++removed_below;
    } else {
      removed_self = removed_self || q == rank.below;
    }
  }
  std::uint64_t added_below = 0;
  bool added_self = false;
  for (std::uint64_t a;;) {  // sorted: stop at the first addition above `object`
    if (!additions.next(a)) return false;
    if (a > object) break;
    if (a < object) ++added_below;
    added_self = added_self || a == object;
  }
  rank.present = added_self || (rank.present && !removed_self);
  rank.below = rank.below - removed_below + added_below;
  return true;
}

}  // namespace

std::uint64_t block_index_size(std::uint32_t cells, std::uint32_t shift) noexcept {
  const std::uint64_t blocks = (std::uint64_t{cells} + (std::uint64_t{1} << shift) - 1) >> shift;
  return 4 * blocks + 2 * (cells - blocks);
}

std::uint64_t cell_start(const PvsSection& section, std::uint32_t cell) noexcept {
  if (!section.coded) return load_u32(section.offsets + 4 * std::size_t{cell});
  if (cell == section.cell_count) return section.payload_size;
  // Block b: a u32 start, then u16 offsets from it for its other cells (FORMAT.md).
  const std::uint32_t shift = section.block_shift;
  const std::size_t record = 4 + 2 * ((std::size_t{1} << shift) - 1);
  const unsigned char* block = section.offsets + (std::size_t{cell} >> shift) * record;
  const std::uint32_t i = cell & ((1u << shift) - 1);
  return std::uint64_t{load_u32(block)} + (i == 0 ? 0 : load_u16(block + 2 + 2 * i));
}

void prefetch_pvs_start(const PvsSection& section, std::uint32_t cell) noexcept {
  if (!section.coded) {
    URBANPVS_PREFETCH(section.offsets + 4 * std::size_t{cell});
    return;
  }
  const std::uint32_t shift = section.block_shift;
  const std::size_t record = 4 + 2 * ((std::size_t{1} << shift) - 1);
  const unsigned char* block = section.offsets + (std::size_t{cell} >> shift) * record;
  const std::uint32_t i = cell & ((1u << shift) - 1);
  URBANPVS_PREFETCH(block);
  if (i != 0) URBANPVS_PREFETCH(block + 2 + 2 * i);  // a block may straddle two lines
}

bool payload_range(const PvsSection& section, std::uint32_t cell, std::uint32_t& begin,
                   std::uint32_t& end) noexcept {
  if (cell >= section.cell_count) return false;
  const std::uint64_t b = cell_start(section, cell), e = cell_start(section, cell + 1);
  if (b > e || e > section.payload_size) return false;
  begin = static_cast<std::uint32_t>(b);
  end = static_cast<std::uint32_t>(e);
  return true;
}

bool read_payload_header(const PvsSection& section, std::uint32_t cell,
                         PayloadHeader& header) noexcept {
  std::uint32_t begin, end;
  if (!payload_range(section, cell, begin, end) || begin == end) return false;
  const unsigned char* p = section.payload + begin;
  const unsigned char* stop = section.payload + end;
  const unsigned kind_byte = *p++;
  const unsigned kind = section.coded ? kind_byte & 3u : kind_byte;
  const unsigned orders = section.coded ? kind_byte >> 2 : 0;
  if (kind > static_cast<unsigned>(PvsKind::kDiff)) return false;
  // Coded: a list's order is below 32 (bit 7 clear), a bitset has none; a diff's two 3-bit
  // orders take every value.
  if ((kind == static_cast<unsigned>(PvsKind::kDeltaList) && orders > kMaxExpGolombOrder) ||
      (kind == static_cast<unsigned>(PvsKind::kBitset) && orders != 0)) {
    return false;
  }
  header.kind = static_cast<PvsKind>(kind);
  header.coded = section.coded;
  header.orders = static_cast<std::uint8_t>(orders);
  header.count = 0;  // a coded diff's is derived (resolve_chain)
  if (!(section.coded && header.kind == PvsKind::kDiff) && !read_varint(p, stop, header.count)) {
    return false;
  }
  header.body = p;
  header.end = stop;
  header.blob_end = section.payload + section.payload_size;
  return true;
}

bool read_diff_header(const PvsSection& section, std::uint32_t cell, const PayloadHeader& header,
                      DiffHeader& diff) noexcept {
  const unsigned char* p = header.body;
  std::uint32_t code;
  if (!read_varint(p, header.end, code) || !read_varint(p, header.end, diff.removed) ||
      !read_varint(p, header.end, diff.added)) {
    return false;
  }
  if (!header.coded) {
    diff.reference = decode_reference(cell, code);
  } else if (code < kNeighbourSlots) {
    diff.reference = section.neighbours != nullptr ? section.neighbours[cell][code] : kNoCell;
  } else {
    diff.reference = decode_reference(cell, code - kNeighbourSlots);
  }
  if (diff.reference >= section.cell_count || diff.reference == cell) return false;
  diff.coded = header.coded;
  diff.removed_order = static_cast<std::uint8_t>(header.orders & 7u);
  diff.added_order = static_cast<std::uint8_t>(header.orders >> 3);
  diff.lists = p;
  diff.end = header.end;
  diff.blob_end = header.blob_end;
  return true;
}

bool resolve_chain(const PvsSection& section, std::uint32_t cell, Chain& chain) noexcept {
  std::uint32_t current = cell;
  for (std::uint32_t step = 0; step <= format::kMaxDiffChain; ++step) {
    chain.cells[step] = current;
    if (!read_payload_header(section, current, chain.headers[step])) return false;
    if (chain.headers[step].kind != PvsKind::kDiff) {
      chain.diff_steps = step;
      if (!section.coded) return true;
      // Coded diffs carry no count: each is its reference's, minus removed, plus added.
      for (std::uint32_t j = step; j-- > 0;) {
        const std::uint64_t reference_count = chain.headers[j + 1].count;
        const DiffHeader& d = chain.diffs[j];
        if (d.removed > reference_count) return false;
        const std::uint64_t count = reference_count - d.removed + d.added;
        if (count > section.object_count) return false;
        chain.headers[j].count = static_cast<std::uint32_t>(count);
      }
      return true;
    }
    if (!read_diff_header(section, current, chain.headers[step], chain.diffs[step])) return false;
    current = chain.diffs[step].reference;
  }
  return false;  // too long, or a cycle
}

Status decode_cell(const PvsSection& section, std::uint32_t cell, std::uint32_t* buffer,
                   std::size_t half, std::size_t& count) noexcept {
  Chain chain;
  if (!resolve_chain(section, cell, chain)) return Status::kMalformedSection;
  const std::uint32_t k = chain.diff_steps;
  const PayloadHeader& base = chain.headers[k];
  std::size_t n = 0;
  if (k == 0) {
    if (!decode_full(base, buffer, half, n) || n != base.count) return Status::kMalformedSection;
    count = n;
    return Status::kOk;
  }
  // The k derived lists alternate between the two halves, starting on the one that makes the
  // last list land in the first half: no final copy. (One diff step needs one half only.)
  std::uint32_t* lists[2] = {buffer, buffer + (k >= 2 ? half : 0)};
  std::uint32_t* current = lists[(k - 1) % 2];
  if (!merge_full(base, chain.diffs[k - 1], current, half, n) || n != chain.headers[k - 1].count) {
    return Status::kMalformedSection;
  }
  for (std::uint32_t j = 2; j <= k; ++j) {
    std::uint32_t* next = lists[(k - j) % 2];
    ArraySource src(current);
    if (!merge(src, static_cast<std::uint32_t>(n), chain.diffs[k - j], next, half, n) ||
        n != chain.headers[k - j].count) {
      return Status::kMalformedSection;
    }
    current = next;
  }
  count = n;
  return Status::kOk;
}

bool merge_decoded(const DiffHeader& diff, const std::uint32_t* reference, std::size_t count,
                   std::uint32_t* out, std::size_t capacity, std::size_t& written) noexcept {
  if (count > UINT32_MAX) return false;
  ArraySource src(reference);
  return merge(src, static_cast<std::uint32_t>(count), diff, out, capacity, written);
}

bool check_diff(const DiffHeader& diff, std::uint32_t count, const std::uint32_t* reference,
                std::size_t reference_count, std::uint32_t object_count, std::uint32_t* scratch,
                std::size_t scratch_size) noexcept {
  if (std::uint64_t{count} + diff.removed != reference_count + std::uint64_t{diff.added}) {
    return false;
  }
  // One pass over the bit stream: the removed positions (increasing, inside the reference) into
  // the scratch, then the additions. (Reading both at once, as a merge does, decodes the
  // removals twice: once to find where the additions start.)
  GapStream removals = diff_removals(diff);
  std::size_t removed = 0;
  for (std::uint64_t q;;) {
    if (!removals.next(q)) return false;
    if (q == kEnd) break;
    if (q >= reference_count || removed == scratch_size) return false;
    scratch[removed++] = static_cast<std::uint32_t>(q);
  }
  // An addition equal to a kept entry would repeat it: it must sit on a removed position.
  // Additions, their positions and the removals all increase: one forward scan of each.
  GapStream additions = diff_additions(diff, removals);
  const std::uint32_t* const end = reference + reference_count;
  const std::uint32_t* at = reference;
  std::size_t r = 0;
  for (std::uint64_t a;;) {
    if (!additions.next(a)) return false;
    if (a == kEnd) return true;
    if (a >= object_count) return false;
    // Galloping from the last match: a few additions spread over a long reference.
    std::size_t step = 1;
    while (step < static_cast<std::size_t>(end - at) && at[step] < a) {
      at += step;
      step *= 2;
    }
    at = std::lower_bound(at, step < static_cast<std::size_t>(end - at) ? at + step + 1 : end,
                          static_cast<std::uint32_t>(a));
    if (at != end && *at == a) {
      const auto position = static_cast<std::uint32_t>(at - reference);
      while (r < removed && scratch[r] < position) ++r;
      if (r == removed || scratch[r] != position) return false;
    }
  }
}

bool cell_contains(const PvsSection& section, std::uint32_t cell, std::uint32_t object) noexcept {
  Chain chain;
  if (!resolve_chain(section, cell, chain)) return false;
  Rank rank;
  if (!rank_in_full(chain.headers[chain.diff_steps], object, rank)) return false;
  for (std::uint32_t j = chain.diff_steps; j-- > 0;) {
    if (!rank_through_diff(chain.diffs[j], object, rank)) return false;
  }
  return rank.present;
}

std::uint32_t encode_reference(std::uint32_t cell, std::uint32_t reference) noexcept {
  const std::uint32_t d = reference - cell;  // wraps: a bijection on 32-bit values
  return (d << 1) ^ (0u - (d >> 31));
}

std::uint32_t decode_reference(std::uint32_t cell, std::uint32_t zigzag) noexcept {
  const std::uint32_t d = (zigzag >> 1) ^ (0u - (zigzag & 1u));
  return cell + d;
}

bool coded_reference_fits(std::uint32_t cell, std::uint32_t reference) noexcept {
  return encode_reference(cell, reference) <= UINT32_MAX - kNeighbourSlots;
}

namespace {

void append_gaps(std::vector<unsigned char>& out, const std::vector<std::uint32_t>& values) {
  std::uint64_t base = 0;
  for (std::uint32_t v : values) {
    append_varint(out, static_cast<std::uint32_t>(v - base));
    base = std::uint64_t{v} + 1;
  }
}

void append_codes(BitWriter& bits, const std::vector<std::uint32_t>& values, unsigned k) {
  std::uint64_t base = 0;
  for (std::uint32_t v : values) {
    bits.code(v - base, k);
    base = std::uint64_t{v} + 1;
  }
}

/// How much larger than a coded delta list a bitset may be and still be chosen (encode_full):
/// 5/4, as an exact ratio of integers.
constexpr std::size_t kCodedBitsetMargin[2] = {5, 4};

/// Largest order of a diff's lists: 3 bits each in the kind byte.
constexpr unsigned kMaxDiffOrder = 7;

}  // namespace

void encode_delta_list(const std::vector<std::uint32_t>& ids, bool coded,
                       std::vector<unsigned char>& out) {
  out.clear();
  std::uint64_t bits = 0;
  const unsigned k = coded ? best_exp_golomb_order(ids, kMaxExpGolombOrder, bits) : 0;
  out.push_back(static_cast<unsigned char>(static_cast<unsigned>(PvsKind::kDeltaList) | k << 2));
  append_varint(out, static_cast<std::uint32_t>(ids.size()));
  if (!coded) {
    append_gaps(out, ids);
    return;
  }
  BitWriter writer(out);
  append_codes(writer, ids, k);
}

void encode_bitset(const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out) {
  out.clear();
  out.push_back(static_cast<unsigned char>(PvsKind::kBitset));
  append_varint(out, static_cast<std::uint32_t>(ids.size()));
  if (ids.empty()) return;  // never chosen: encode_full prefers the 2-byte delta list
  const std::uint32_t first = ids.front() / 8;
  const std::uint32_t size = ids.back() / 8 - first + 1;
  append_varint(out, first);
  append_varint(out, size);
  const std::size_t start = out.size();
  out.resize(start + size, 0);
  for (std::uint32_t id : ids) {
    out[start + (id / 8 - first)] |= static_cast<unsigned char>(1u << (id % 8));
  }
}

void encode_full(const std::vector<std::uint32_t>& ids, bool coded,
                 std::vector<unsigned char>& out) {
  encode_delta_list(ids, coded, out);
  if (ids.empty()) return;
  // Bitset bytes are known without encoding: compare before building it.
  const std::size_t bitset_bytes =
      1 + varint_size(static_cast<std::uint32_t>(ids.size())) + varint_size(ids.front() / 8) +
      varint_size(ids.back() / 8 - ids.front() / 8 + 1) + (ids.back() / 8 - ids.front() / 8 + 1);
  // Coded lists of dense PVSs are about as small as a bitset (a present neighbour costs one bit
  // in both) but decode bit by bit, several times slower than a bitset's bytes: the bitset wins
  // unless it is more than 5/4 of its size (Monaco's 1,145-object PVSs: README, "Real bakes").
  const bool bitset =
      coded ? bitset_bytes * kCodedBitsetMargin[1] <= out.size() * kCodedBitsetMargin[0]
            : bitset_bytes < out.size();
  if (bitset) encode_bitset(ids, out);
}

void encode_diff(std::uint32_t cell, std::uint32_t reference,
                 const std::array<std::uint32_t, 3>& neighbours,
                 const std::vector<std::uint32_t>& reference_ids,
                 const std::vector<std::uint32_t>& ids, bool coded,
                 std::vector<unsigned char>& out) {
  std::vector<std::uint32_t> removed;  // positions in reference_ids
  std::vector<std::uint32_t> added;    // ids
  std::size_t i = 0, j = 0;
  while (i < reference_ids.size() || j < ids.size()) {
    if (j == ids.size() || (i < reference_ids.size() && reference_ids[i] < ids[j])) {
      removed.push_back(static_cast<std::uint32_t>(i++));
    } else if (i == reference_ids.size() || ids[j] < reference_ids[i]) {
      added.push_back(ids[j++]);
    } else {
      ++i;
      ++j;
    }
  }
  std::uint64_t ignored = 0;
  const unsigned kr = coded ? best_exp_golomb_order(removed, kMaxDiffOrder, ignored) : 0;
  const unsigned ka = coded ? best_exp_golomb_order(added, kMaxDiffOrder, ignored) : 0;
  out.clear();
  out.push_back(
      static_cast<unsigned char>(static_cast<unsigned>(PvsKind::kDiff) | kr << 2 | ka << 5));
  if (!coded) {
    append_varint(out, static_cast<std::uint32_t>(ids.size()));
    append_varint(out, encode_reference(cell, reference));
    append_varint(out, static_cast<std::uint32_t>(removed.size()));
    append_varint(out, static_cast<std::uint32_t>(added.size()));
    append_gaps(out, removed);
    append_gaps(out, added);
    return;
  }
  // Coded: no count (the reader derives it), and a neighbour's slot in place of a distance.
  const auto slot = std::find(neighbours.begin(), neighbours.end(), reference);
  append_varint(out, slot != neighbours.end()
                         ? static_cast<std::uint32_t>(slot - neighbours.begin())
                         : encode_reference(cell, reference) + kNeighbourSlots);
  append_varint(out, static_cast<std::uint32_t>(removed.size()));
  append_varint(out, static_cast<std::uint32_t>(added.size()));
  BitWriter writer(out);  // one stream: removals, then additions
  append_codes(writer, removed, kr);
  append_codes(writer, added, ka);
}

}  // namespace urbanpvs::runtime::detail
