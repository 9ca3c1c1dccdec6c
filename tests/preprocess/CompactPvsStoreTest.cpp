// SPDX-License-Identifier: GPL-3.0-or-later
// CompactPvsStore: every list comes back as stored, from empty to every object, across word and
// byte boundaries of the bitset, and each takes the smaller of its two codings (that a file
// assembled from the store has the bytes of the lists: PvsFileAssemblyTest).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "urbanpvs/preprocess/bake/CompactPvsStore.hpp"

using urbanpvs::preprocess::CompactPvsStore;

namespace {

std::size_t varint_bytes(std::uint64_t v) {
  std::size_t n = 1;
  while (v >= 0x80) v >>= 7, ++n;
  return n;
}

TEST(CompactPvsStore, ListsComeBackAsStoredInTheSmallerCoding) {
  std::mt19937_64 rng(7);
  for (std::uint32_t objects : {1u, 7u, 8u, 9u, 63u, 64u, 65u, 1000u, 70000u}) {
    for (double density : {0.0, 0.001, 0.05, 0.2, 0.5, 0.95, 1.0}) {
      SCOPED_TRACE("objects " + std::to_string(objects) + ", density " + std::to_string(density));
      std::bernoulli_distribution keep(density);
      std::vector<std::uint32_t> pvs;
      for (std::uint32_t o = 0; o < objects; ++o)
        if (keep(rng)) pvs.push_back(o);
      if (density > 0 && pvs.empty()) pvs.push_back(objects - 1);  // the last object, alone
      CompactPvsStore store(3, objects);
      store.store(1, pvs);
      EXPECT_EQ(store.load(1), pvs);
      EXPECT_EQ(store.size(1), pvs.size());
      EXPECT_TRUE(store.load(0).empty()) << "a cell never stored";
      std::size_t gaps = 1;
      std::uint32_t previous = 0;
      for (std::uint32_t o : pvs) gaps += varint_bytes(o - previous), previous = o;
      const std::size_t bitset = 1 + (objects + 7) / 8;
      EXPECT_LE(store.bytes(), std::min(gaps, bitset) + 1 /* vector capacity slack */);
      store.store(1, {});  // replaced
      EXPECT_TRUE(store.load(1).empty());
      const std::vector<std::uint32_t> beyond{objects};
      EXPECT_THROW(store.store(2, beyond), std::out_of_range) << "an index past the objects";
    }
  }
}

}  // namespace
