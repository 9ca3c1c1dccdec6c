// SPDX-License-Identifier: MIT
#pragma once

// Little-endian encoding into a growing byte vector, the mirror of ByteReader.hpp. Values are
// written byte by byte so the output never depends on the host.

#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace urbanpvs::runtime::detail {

inline void append_varint(std::vector<unsigned char>& out, std::uint32_t value) {
  while (value >= 0x80) {
    out.push_back(static_cast<unsigned char>(value | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<unsigned char>(value));
}

/// Bytes append_varint writes for `value`.
inline std::size_t varint_size(std::uint32_t value) noexcept {
  std::size_t n = 1;
  while (value >= 0x80) {
    value >>= 7;
    ++n;
  }
  return n;
}

class ByteWriter {
 public:
  std::vector<unsigned char>& bytes() noexcept { return out_; }
  std::size_t size() const noexcept { return out_.size(); }

  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { fixed(v, 2); }
  void u32(std::uint32_t v) { fixed(v, 4); }
  void u64(std::uint64_t v) { fixed(v, 8); }
  void f64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    fixed(bits, 8);
  }
  void f32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    fixed(bits, 4);
  }
  void varint(std::uint32_t v) { append_varint(out_, v); }
  void raw(const unsigned char* data, std::size_t n) { out_.insert(out_.end(), data, data + n); }
  /// u32 length + bytes; the caller has checked the length fits.
  void string(std::string_view s) {
    u32(static_cast<std::uint32_t>(s.size()));
    raw(reinterpret_cast<const unsigned char*>(s.data()), s.size());
  }
  /// The bytes of `s`, without a length.
  void string_bytes(std::string_view s) {
    raw(reinterpret_cast<const unsigned char*>(s.data()), s.size());
  }
  /// Overwrites 4 bytes at `offset` (for fields known only later, such as checksums).
  void patch_u32(std::size_t offset, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out_[offset + i] = static_cast<unsigned char>(v >> (8 * i));
  }

 private:
  void fixed(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(static_cast<unsigned char>(v >> (8 * i)));
  }

  std::vector<unsigned char> out_;
};

}  // namespace urbanpvs::runtime::detail
