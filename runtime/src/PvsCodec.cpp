// SPDX-License-Identifier: MIT
#include "PvsCodec.hpp"

#include <algorithm>

#include "Bits.hpp"
#include "ByteReader.hpp"
#include "ByteWriter.hpp"

namespace urbanpvs::runtime::detail {
namespace {

using format::PvsKind;

/// "No further element" in the merge streams (above every 32-bit value).
constexpr std::uint64_t kEnd = UINT64_MAX;

/// A strictly increasing list stored as varint gaps (first value, then value - previous - 1).
class GapStream {
 public:
  GapStream(const unsigned char* p, const unsigned char* end, std::uint32_t count) noexcept
      : p_(p), end_(end), left_(count) {}

  /// Next value, or kEnd once `count` values were read (then the stream must be exactly at its
  /// end). False on malformed data.
  bool next(std::uint64_t& value) noexcept {
    if (left_ == 0) {
      value = kEnd;
      return p_ == end_;
    }
    std::uint32_t gap;
    if (!read_varint(p_, end_, gap)) return false;
    value = base_ + gap;
    if (value > UINT32_MAX) return false;
    base_ = value + 1;
    --left_;
    return true;
  }

 private:
  const unsigned char* p_;
  const unsigned char* end_;
  std::uint32_t left_;
  std::uint64_t base_ = 0;
};

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

/// Skips `n` varints; false when they run past `end`.
bool skip_varints(const unsigned char*& p, const unsigned char* end, std::uint32_t n) noexcept {
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint32_t ignored;
    if (!read_varint(p, end, ignored)) return false;
  }
  return true;
}

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

bool decode_full(const PayloadHeader& h, std::uint32_t* out, std::size_t capacity,
                 std::size_t& written) noexcept {
  if (h.kind == PvsKind::kDeltaList) {
    DeltaSource src(h);
    return drain(src, h.count, out, capacity, written);
  }
  BitsetSource src(h);
  return drain(src, h.count, out, capacity, written);
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
  const unsigned char* additions_begin = d.lists;
  if (!skip_varints(additions_begin, d.end, d.removed)) return false;
  DiffCursor c{GapStream(d.lists, additions_begin, d.removed),
               GapStream(additions_begin, d.end, d.added), 0, 0};
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
  if (base.kind == PvsKind::kDeltaList) {
    DeltaSource src(base);
    return merge(src, base.count, d, out, capacity, written);
  }
  BitsetSource src(base);
  return merge(src, base.count, d, out, capacity, written);
}

/// Number of elements below `object` in a list, and whether `object` is in it.
struct Rank {
  std::uint64_t below = 0;
  bool present = false;
};

bool rank_in_full(const PayloadHeader& h, std::uint32_t object, Rank& rank) noexcept {
  if (h.kind == PvsKind::kDeltaList) {
    DeltaSource src(h);
    for (std::uint32_t i = 0; i < h.count; ++i) {
      std::uint64_t v;
      if (!src.next(v)) return false;
      if (v >= object) {  // sorted: stop at the first element not below `object`
        rank = {i, v == object};
        return true;
      }
    }
    rank = {h.count, false};
    return src.finish();
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
  const unsigned char* additions_begin = d.lists;
  if (!skip_varints(additions_begin, d.end, d.removed)) return false;
  GapStream removals(d.lists, additions_begin, d.removed);
  GapStream additions(additions_begin, d.end, d.added);
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

bool read_payload_header(const PvsSection& section, std::uint32_t cell,
                         PayloadHeader& header) noexcept {
  if (cell >= section.cell_count) return false;
  const std::uint32_t begin = load_u32(section.offsets + 4 * std::size_t{cell});
  const std::uint32_t end = load_u32(section.offsets + 4 * (std::size_t{cell} + 1));
  if (begin > end || end > section.payload_size) return false;
  const unsigned char* p = section.payload + begin;
  const unsigned char* stop = section.payload + end;
  if (p == stop || *p > static_cast<unsigned char>(PvsKind::kDiff)) return false;
  header.kind = static_cast<PvsKind>(*p++);
  if (!read_varint(p, stop, header.count)) return false;
  header.body = p;
  header.end = stop;
  return true;
}

bool read_diff_header(const PvsSection& section, std::uint32_t cell, const PayloadHeader& header,
                      DiffHeader& diff) noexcept {
  const unsigned char* p = header.body;
  std::uint32_t zigzag;
  if (!read_varint(p, header.end, zigzag) || !read_varint(p, header.end, diff.removed) ||
      !read_varint(p, header.end, diff.added)) {
    return false;
  }
  diff.reference = decode_reference(cell, zigzag);
  if (diff.reference >= section.cell_count || diff.reference == cell) return false;
  diff.lists = p;
  diff.end = header.end;
  return true;
}

bool resolve_chain(const PvsSection& section, std::uint32_t cell, Chain& chain) noexcept {
  std::uint32_t current = cell;
  for (std::uint32_t step = 0; step <= format::kMaxDiffChain; ++step) {
    chain.cells[step] = current;
    if (!read_payload_header(section, current, chain.headers[step])) return false;
    if (chain.headers[step].kind != PvsKind::kDiff) {
      chain.diff_steps = step;
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
                std::size_t reference_count, std::uint32_t object_count) noexcept {
  const unsigned char* additions_begin = diff.lists;
  if (!skip_varints(additions_begin, diff.end, diff.removed)) return false;
  GapStream removals(diff.lists, additions_begin, diff.removed);
  GapStream additions(additions_begin, diff.end, diff.added);
  std::uint64_t removal, addition;
  if (!removals.next(removal) || !additions.next(addition)) return false;
  // An addition equal to a kept entry would repeat it: it must sit on a removed position.
  // Additions and their positions both increase, so one pass over each list does.
  const std::uint32_t* const end = reference + reference_count;
  const std::uint32_t* at = reference;
  while (addition != kEnd) {
    if (addition >= object_count) return false;
    at = std::lower_bound(at, end, static_cast<std::uint32_t>(addition));
    if (at != end && *at == addition) {
      const std::uint64_t position = static_cast<std::uint64_t>(at - reference);
      while (removal < position) {
        if (!removals.next(removal)) return false;
      }
      if (removal != position) return false;
    }
    if (!additions.next(addition)) return false;
  }
  while (removal != kEnd) {  // the positions not met above, each inside the reference
    if (removal >= reference_count || !removals.next(removal)) return false;
  }
  return std::uint64_t{count} + diff.removed == reference_count + std::uint64_t{diff.added};
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

namespace {

void append_gaps(std::vector<unsigned char>& out, const std::vector<std::uint32_t>& values) {
  std::uint64_t base = 0;
  for (std::uint32_t v : values) {
    append_varint(out, static_cast<std::uint32_t>(v - base));
    base = std::uint64_t{v} + 1;
  }
}

}  // namespace

void encode_delta_list(const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out) {
  out.clear();
  out.push_back(static_cast<unsigned char>(PvsKind::kDeltaList));
  append_varint(out, static_cast<std::uint32_t>(ids.size()));
  append_gaps(out, ids);
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

void encode_full(const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out) {
  encode_delta_list(ids, out);
  if (ids.empty()) return;
  // Bitset bytes are known without encoding: compare before building it.
  const std::size_t bitset_bytes =
      1 + varint_size(static_cast<std::uint32_t>(ids.size())) + varint_size(ids.front() / 8) +
      varint_size(ids.back() / 8 - ids.front() / 8 + 1) + (ids.back() / 8 - ids.front() / 8 + 1);
  if (bitset_bytes < out.size()) encode_bitset(ids, out);
}

void encode_diff(std::uint32_t cell, std::uint32_t reference,
                 const std::vector<std::uint32_t>& reference_ids,
                 const std::vector<std::uint32_t>& ids, std::vector<unsigned char>& out) {
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
  out.clear();
  out.push_back(static_cast<unsigned char>(PvsKind::kDiff));
  append_varint(out, static_cast<std::uint32_t>(ids.size()));
  append_varint(out, encode_reference(cell, reference));
  append_varint(out, static_cast<std::uint32_t>(removed.size()));
  append_varint(out, static_cast<std::uint32_t>(added.size()));
  append_gaps(out, removed);
  append_gaps(out, added);
}

}  // namespace urbanpvs::runtime::detail
