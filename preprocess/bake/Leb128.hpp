// SPDX-License-Identifier: GPL-3.0-or-later
// LEB128 varints, the coding of the bake's journal records and of the PVS lists it holds in
// memory (CompactPvsStore): small numbers (gaps between the object indices of a sorted list)
// in a byte each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace urbanpvs::preprocess::detail {

inline void put_varint(std::vector<unsigned char>& out, std::uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<unsigned char>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<unsigned char>(v));
}

/// Reads varints from a bounded span; any overrun or over-long encoding fails.
class VarintReader {
 public:
  VarintReader(const unsigned char* p, std::size_t n) : p_(p), end_(p + n) {}
  bool next(std::uint64_t& v) {
    v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (p_ == end_) return false;
      const unsigned char b = *p_++;
      if (shift == 63 && b > 1) return false;
      v |= std::uint64_t{b & 0x7fu} << shift;
      if (!(b & 0x80)) return true;
    }
    return false;
  }
  bool at_end() const { return p_ == end_; }

 private:
  const unsigned char* p_;
  const unsigned char* end_;
};

}  // namespace urbanpvs::preprocess::detail
