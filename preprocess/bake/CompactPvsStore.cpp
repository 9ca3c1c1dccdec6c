// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/CompactPvsStore.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

#include "Leb128.hpp"

namespace urbanpvs::preprocess {
namespace {

enum Kind : unsigned char { kGaps = 0, kBitset = 1 };

}  // namespace

CompactPvsStore::CompactPvsStore(std::size_t cells, std::uint32_t objects)
    : objects_(objects), lists_(cells), sizes_(cells, 0) {}

void CompactPvsStore::store(std::uint32_t cell, std::span<const std::uint32_t> pvs) {
  // The bitset is written at the indices: one out of range would write past it.
  if (!pvs.empty() && pvs.back() >= objects_)
    throw std::out_of_range("CompactPvsStore: object " + std::to_string(pvs.back()) + " of " +
                            std::to_string(objects_));
  std::vector<unsigned char>& out = lists_[cell];
  out.assign(1, kGaps);
  std::uint32_t previous = 0;
  for (std::uint32_t o : pvs) {
    detail::put_varint(out, o - previous);
    previous = o;
  }
  const std::size_t bitset = 1 + (std::size_t{objects_} + 7) / 8;
  if (out.size() > bitset) {
    out.assign(bitset, 0);
    out[0] = kBitset;
    for (std::uint32_t o : pvs) out[1 + o / 8] |= static_cast<unsigned char>(1u << (o % 8));
  }
  out.shrink_to_fit();
  sizes_[cell] = static_cast<std::uint32_t>(pvs.size());
}

void CompactPvsStore::load(std::uint32_t cell, std::vector<std::uint32_t>& pvs) const {
  const std::vector<unsigned char>& in = lists_[cell];
  pvs.clear();
  pvs.reserve(sizes_[cell]);
  if (in.empty()) return;
  if (in[0] == kBitset) {
    // Eight bytes at a time; the last word is padded with zeros.
    const std::size_t bytes = in.size() - 1;
    for (std::size_t at = 0; at < bytes; at += 8) {
      std::uint64_t word = 0;
      std::memcpy(&word, in.data() + 1 + at, std::min<std::size_t>(8, bytes - at));
      if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap64(word);
      while (word != 0) {
        pvs.push_back(static_cast<std::uint32_t>(8 * at) +
                      static_cast<std::uint32_t>(std::countr_zero(word)));
        word &= word - 1;
      }
    }
    return;
  }
  detail::VarintReader r(in.data() + 1, in.size() - 1);
  std::uint64_t gap = 0, object = 0;
  for (std::uint32_t k = 0; k < sizes_[cell]; ++k) {
    if (!r.next(gap)) throw std::logic_error("CompactPvsStore: a list ends early");
    object += gap;
    pvs.push_back(static_cast<std::uint32_t>(object));
  }
}

std::vector<std::uint32_t> CompactPvsStore::load(std::uint32_t cell) const {
  std::vector<std::uint32_t> pvs;
  load(cell, pvs);
  return pvs;
}

std::size_t CompactPvsStore::bytes() const {
  std::size_t n = 0;
  for (const auto& l : lists_) n += l.capacity();
  return n;
}

}  // namespace urbanpvs::preprocess
