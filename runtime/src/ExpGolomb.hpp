// SPDX-License-Identifier: MIT
#pragma once

// Exp-Golomb codes of order k in an LSB-first bit stream: the gaps of the PVS lists of format
// 2.2 (FORMAT.md, "pvs, coding 2"). A PVS lists nearby objects, so most gaps are a few ids and
// a few are thousands: a varint spends 8 bits on a gap of 0, exp-Golomb k + 1, and its code
// length grows with the logarithm of the gap, so long gaps never cost much. The writer picks
// k per list.
//
// Code of g with order k: v = g + 2^k has n = bit_width(v) bits; the stream gets n - k - 1
// zero bits, a one bit, then the n - 1 low bits of v (least significant first): 2n - k - 1
// bits in all. Bits fill each byte from its least significant bit; the last byte is padded
// with zeros.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "Bits.hpp"
#include "ByteReader.hpp"

namespace urbanpvs::runtime::detail {

/// Largest order a list may declare: gaps are below 2^32.
inline constexpr unsigned kMaxExpGolombOrder = 31;

/// Bits of the order-k code of `gap`.
inline std::uint64_t exp_golomb_bits(std::uint64_t gap, unsigned k) noexcept {
  return 2 * std::uint64_t{bit_width64(gap + (std::uint64_t{1} << k))} - k - 1;
}

/// Appends codes to a byte vector, LSB first.
class BitWriter {
 public:
  explicit BitWriter(std::vector<unsigned char>& out) noexcept : out_(out) {}
  ~BitWriter() { flush(); }
  BitWriter(const BitWriter&) = delete;
  BitWriter& operator=(const BitWriter&) = delete;

  void code(std::uint64_t gap, unsigned k) {
    const std::uint64_t v = gap + (std::uint64_t{1} << k);
    const unsigned n = bit_width64(v);
    bits(0, n - k - 1);
    bits(1, 1);
    bits(v & ((std::uint64_t{1} << (n - 1)) - 1), n - 1);
  }
  /// The last partial byte, zero padded; later codes start on a fresh byte.
  void flush() {
    if (used_ > 0) out_.push_back(static_cast<unsigned char>(acc_));
    acc_ = 0;
    used_ = 0;
  }

 private:
  void bits(std::uint64_t value, unsigned n) {  // n <= 33
    for (unsigned i = 0; i < n; ++i) {
      acc_ |= static_cast<unsigned>((value >> i) & 1u) << used_;
      if (++used_ == 8) {
        out_.push_back(static_cast<unsigned char>(acc_));
        acc_ = 0;
        used_ = 0;
      }
    }
  }

  std::vector<unsigned char>& out_;
  unsigned acc_ = 0;
  unsigned used_ = 0;
};

/// Reads codes from the bytes [data, data + size). It may look at the bytes up to
/// data + readable (>= size: the rest of the pvs blob, so that a small payload is read 8 bytes
/// at a time) but never further: past that the stream reads as zeros. A code that would end
/// past `size` fails, whatever those bytes hold.
class BitReader {
 public:
  BitReader(const unsigned char* data, std::size_t size, std::size_t readable) noexcept
      : data_(data),
        size_(size),
        readable_(readable < size ? size : readable),
        bits_(std::uint64_t{size} * 8) {}
  BitReader(const unsigned char* data, std::size_t size) noexcept : BitReader(data, size, size) {}

  std::uint64_t position() const noexcept { return position_; }

  /// The next code of order k (<= kMaxExpGolombOrder) into `gap` (< 2^33); false past the end.
  bool code(unsigned k, std::uint64_t& gap) noexcept {
    // Fast path: the whole code lies in the bits held in window_. The chain from one code to
    // the next is then a trailing-zero count and a shift, with no load in it (reading each code
    // from memory, as peek does, put a load on that chain: about twice the time per code).
    // (Bit 63 stops the count: a code whose one bit lies that far is not held anyway.)
    const unsigned zeros = count_trailing_zeros64(window_ | (std::uint64_t{1} << 63));
    const unsigned length = 2 * zeros + 1 + k;  // the code's bits: zeros, the one, low bits
    const unsigned low = zeros + k;             // n - 1 bits of v below its top bit
    if (length <= held_ && low <= 32) {
      const std::uint64_t v =
          (std::uint64_t{1} << low) | ((window_ >> (zeros + 1)) & ((std::uint64_t{1} << low) - 1));
      if (position_ + length > bits_) return false;
      window_ >>= length;
      held_ -= length;
      position_ += length;
      gap = v - (std::uint64_t{1} << k);
      return true;
    }
    return code_from_memory(k, gap);
  }

  /// Whether the stream ends here: the rest of the current byte is zero padding and no byte
  /// follows (the encoding is exact, like a varint's).
  bool at_padded_end() const noexcept {
    if ((position_ + 7) / 8 != size_) return false;
    const unsigned used = static_cast<unsigned>(position_ % 8);
    return used == 0 || (data_[size_ - 1] >> used) == 0;
  }

 private:
  /// code() when the window does not hold the whole code: read at position_ and refill.
  bool code_from_memory(unsigned k, std::uint64_t& gap) noexcept {
    std::uint64_t word = peek(position_);
    if (word == 0) return false;  // no one bit in the next 57: longer than any 33-bit value
    const unsigned zeros = count_trailing_zeros64(word);
    const unsigned low = zeros + k;  // n - 1 bits of v below its top bit
    if (low > 32) return false;      // v >= 2^34
    std::uint64_t start = position_ + zeros + 1;
    if (zeros + 1 + low > 57) {  // rare: the low bits start beyond this window
      word = peek(start);
    } else {
      word >>= zeros + 1;
    }
    const std::uint64_t v = (std::uint64_t{1} << low) | (word & ((std::uint64_t{1} << low) - 1));
    start += low;
    if (start > bits_) return false;
    position_ = start;
    gap = v - (std::uint64_t{1} << k);
    window_ = peek(position_);  // 57 bits from here for the codes that follow
    held_ = 57;
    return true;
  }

  /// 57 or more bits from `at` (zeros past the readable bytes).
  std::uint64_t peek(std::uint64_t at) const noexcept {
    const std::uint64_t byte = at / 8;
    if (byte + 8 <= readable_) return load_u64(data_ + byte) >> (at % 8);
    std::uint64_t word = 0;
    for (std::uint64_t i = byte, shift = 0; i < readable_; ++i, shift += 8) {
      word |= std::uint64_t{data_[i]} << shift;
    }
    return word >> (at % 8);
  }

  const unsigned char* data_;
  std::size_t size_;
  std::size_t readable_;
  std::uint64_t bits_;
  std::uint64_t position_ = 0;
  std::uint64_t window_ = 0;  ///< the bits from position_ on; the low held_ of them are read
  unsigned held_ = 0;
};

/// The order (from k0 - 2 to k0 + 2 around the mean gap's width k0, moved into [0, max_k]) that
/// codes the gaps of the strictly increasing `values` in the fewest bits, and those bits.
inline unsigned best_exp_golomb_order(const std::vector<std::uint32_t>& values, unsigned max_k,
                                      std::uint64_t& bits) {
  bits = 0;
  if (values.empty()) return 0;
  const std::uint64_t span = std::uint64_t{values.back()} + 1 - values.size();  // sum of gaps
  const unsigned k0 = bit_width64(span / values.size());
  unsigned best = 0;
  bool first = true;
  // The window is clamped into [0, max_k], so it is never empty: long gaps with a small
  // max_k still get the largest order.
  const unsigned hi = k0 + 2 < max_k ? k0 + 2 : max_k;
  const unsigned lo = k0 > hi + 2 ? hi - (hi < 4 ? hi : 4) : (k0 > 2 ? k0 - 2 : 0);
  for (unsigned k = lo; k <= hi; ++k) {
    std::uint64_t total = 0, base = 0;
    for (std::uint32_t v : values) {
      total += exp_golomb_bits(v - base, k);
      base = std::uint64_t{v} + 1;
    }
    if (first || total < bits) {
      bits = total;
      best = k;
      first = false;
    }
  }
  return best;
}

}  // namespace urbanpvs::runtime::detail
