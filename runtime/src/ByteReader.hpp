// SPDX-License-Identifier: MIT
#pragma once

// Bounds-checked little-endian decoding. Every multi-byte value is assembled byte by byte, so
// the format is independent of the host's endianness and alignment (compilers fuse the shifts
// into one load on little-endian machines).

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace urbanpvs::runtime::detail {

inline std::uint16_t load_u16(const unsigned char* p) noexcept {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}

inline std::uint32_t load_u32(const unsigned char* p) noexcept {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

inline std::uint64_t load_u64(const unsigned char* p) noexcept {
  return static_cast<std::uint64_t>(load_u32(p)) |
         (static_cast<std::uint64_t>(load_u32(p + 4)) << 32);
}

inline double bits_to_f64(std::uint64_t bits) noexcept {
  double value;
  std::memcpy(&value, &bits, sizeof value);  // the C++17 way to reinterpret bits
  return value;
}

inline float bits_to_f32(std::uint32_t bits) noexcept {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

inline double load_f64(const unsigned char* p) noexcept {
  return bits_to_f64(load_u64(p));
}
inline float load_f32(const unsigned char* p) noexcept {
  return bits_to_f32(load_u32(p));
}

/// LEB128 varint of at most 32 bits at [p, end). Rejects truncation, values above 2^32 - 1 and
/// non-minimal encodings (a trailing zero byte), so every value has exactly one encoding.
/// Advances p on success.
inline bool read_varint(const unsigned char*& p, const unsigned char* end,
                        std::uint32_t& value) noexcept {
  if (p == end) return false;
  std::uint32_t byte = *p;
  if (byte < 0x80) {  // fast paths: nearly all PVS gaps fit in 7 or 14 bits
    ++p;
    value = byte;
    return true;
  }
  if (end - p >= 2 && p[1] - 1u < 0x7Fu) {  // second byte in [1, 0x7F]: last and canonical
    value = (byte & 0x7Fu) | (std::uint32_t{p[1]} << 7);
    p += 2;
    return true;
  }
  const unsigned char* q = p + 1;
  std::uint32_t result = byte & 0x7F;
  for (unsigned shift = 7; shift <= 28; shift += 7) {
    if (q == end) return false;
    byte = *q++;
    if (shift == 28 && byte > 0x0F) return false;  // more than 32 bits
    result |= (byte & 0x7F) << shift;
    if (byte < 0x80) {
      if (byte == 0) return false;  // non-minimal
      p = q;
      value = result;
      return true;
    }
  }
  return false;
}

/// Sequential reader over a byte range. Every read checks the remaining length first and
/// fails (returning false, leaving the position unchanged) instead of reading past the end.
class ByteReader {
 public:
  ByteReader(const unsigned char* data, std::size_t size) noexcept
      : begin_(data), cur_(data), end_(data + size) {}

  std::size_t position() const noexcept { return static_cast<std::size_t>(cur_ - begin_); }
  std::size_t remaining() const noexcept { return static_cast<std::size_t>(end_ - cur_); }
  const unsigned char* current() const noexcept { return cur_; }

  bool u8(std::uint8_t& v) noexcept {
    return fixed(1, [&](const unsigned char* p) { v = *p; });
  }
  bool u16(std::uint16_t& v) noexcept {
    return fixed(2, [&](const unsigned char* p) { v = load_u16(p); });
  }
  bool u32(std::uint32_t& v) noexcept {
    return fixed(4, [&](const unsigned char* p) { v = load_u32(p); });
  }
  bool u64(std::uint64_t& v) noexcept {
    return fixed(8, [&](const unsigned char* p) { v = load_u64(p); });
  }
  bool f64(double& v) noexcept {
    return fixed(8, [&](const unsigned char* p) { v = load_f64(p); });
  }
  bool varint(std::uint32_t& v) noexcept { return read_varint(cur_, end_, v); }

  /// Takes `n` bytes: `out` points at them.
  bool bytes(std::size_t n, const unsigned char*& out) noexcept {
    if (n > remaining()) return false;
    out = cur_;
    cur_ += n;
    return true;
  }

  /// u32 length followed by that many bytes.
  bool string(const unsigned char*& data, std::uint32_t& length) noexcept {
    const unsigned char* start = cur_;
    if (!u32(length) || !bytes(length, data)) {
      cur_ = start;
      return false;
    }
    return true;
  }

 private:
  template <class Store>
  bool fixed(std::size_t n, Store store) noexcept {
    if (n > remaining()) return false;
    store(cur_);
    cur_ += n;
    return true;
  }

  const unsigned char* begin_;
  const unsigned char* cur_;
  const unsigned char* end_;
};

/// a * b when it fits in 64 bits.
inline bool checked_mul(std::uint64_t a, std::uint64_t b, std::uint64_t& out) noexcept {
  if (a != 0 && b > UINT64_MAX / a) return false;
  out = a * b;
  return true;
}

/// a + b when it fits in 64 bits.
inline bool checked_add(std::uint64_t a, std::uint64_t b, std::uint64_t& out) noexcept {
  if (b > UINT64_MAX - a) return false;
  out = a + b;
  return true;
}

}  // namespace urbanpvs::runtime::detail
