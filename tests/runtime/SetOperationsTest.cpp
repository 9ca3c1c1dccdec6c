// SPDX-License-Identifier: MIT
// pvs_union and pvs_delta (PvsDecoder::decode_union / decode_delta) against the standard
// library's set algorithms on the bake's own lists, and the decoder's cache of decoded cells
// against the bake's lists, with and without diff chains in the file and with caches of one,
// three (one set, smaller than its ways), 20 (two sets, fewer slots than the test's 40 agents) and
// 64 cells.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <random>
#include <tuple>
#include <vector>

#include "SyntheticCity.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace {

namespace rt = urbanpvs::runtime;
using Ids = std::vector<std::uint32_t>;

Ids ids(rt::IndexSpan s) {
  return Ids(s.begin(), s.end());
}

Ids reference_union(const rt::PvsBake& bake, const Ids& cells) {
  Ids out;
  for (std::uint32_t c : cells) {
    Ids merged;
    std::set_union(out.begin(), out.end(), bake.cells[c].pvs.begin(), bake.cells[c].pvs.end(),
                   std::back_inserter(merged));
    out.swap(merged);
  }
  return out;
}

Ids difference(const Ids& a, const Ids& b) {
  Ids out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

/// The file's diff chain bound and the decoder's cached cells.
using Setup = std::tuple<std::uint32_t, std::size_t>;

class SetOperations : public ::testing::TestWithParam<Setup> {
 protected:
  void SetUp() override {
    urbanpvs::test::SyntheticCityOptions city;
    city.extent_m = 800;
    city.squares = 24;  // 1,152 cells
    city.objects = 900;
    bake_ = urbanpvs::test::synthetic_city(city);
    rt::EncodeOptions options;
    options.max_diff_chain = std::get<0>(GetParam());
    bytes_ = rt::encode(bake_, options);
    ASSERT_EQ(rt::PvsFile::open(bytes_.data(), bytes_.size(), file_), rt::Status::kOk);
  }
  std::size_t cached() const { return std::get<1>(GetParam()); }

  rt::PvsBake bake_;
  std::vector<std::byte> bytes_;
  rt::PvsFile file_;
};

TEST_P(SetOperations, UnionOfRandomCellsMatchesSetUnion) {
  rt::PvsDecoder decoder(file_, cached());
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::uint32_t> cell(0, file_.cell_count() - 1);
  for (int trial = 0; trial < 300; ++trial) {
    Ids cells(1 + trial % 9);
    for (std::uint32_t& c : cells) c = cell(rng);
    if (trial % 5 == 0) cells.push_back(cells.front());  // a cell twice changes nothing
    ASSERT_EQ(decoder.decode_union(cells.data(), cells.size()), rt::Status::kOk);
    ASSERT_EQ(ids(decoder.view()), reference_union(bake_, cells)) << "trial " << trial;
  }
}

TEST_P(SetOperations, UnionOfACellAndItsNeighboursForPrefetching) {
  rt::PvsDecoder decoder(file_, cached());
  std::size_t grew = 0;
  for (std::uint32_t c = 0; c < file_.cell_count(); c += 3) {
    Ids ring{c};
    for (std::uint32_t n : bake_.cells[c].neighbours)
      if (n != rt::kNoCell) ring.push_back(n);
    ASSERT_EQ(decoder.decode_union(ring.data(), ring.size()), rt::Status::kOk);
    const Ids got = ids(decoder.view());
    ASSERT_EQ(got, reference_union(bake_, ring)) << "cell " << c;
    grew += got.size() > bake_.cells[c].pvs.size();
  }
  EXPECT_GT(grew, 0u);  // the neighbours add objects somewhere: the union is not one cell's PVS
}

TEST_P(SetOperations, DeltaAcrossEveryEdgeAndBetweenRandomCells) {
  rt::PvsDecoder decoder(file_, cached());
  auto check = [&](std::uint32_t from, std::uint32_t to) {
    ASSERT_EQ(decoder.decode_delta(from, to), rt::Status::kOk);
    const Ids& before = bake_.cells[from].pvs;
    const Ids& after = bake_.cells[to].pvs;
    ASSERT_EQ(ids(decoder.entered()), difference(after, before)) << from << " -> " << to;
    ASSERT_EQ(ids(decoder.left()), difference(before, after)) << from << " -> " << to;
    ASSERT_EQ(ids(decoder.view()), after);
  };
  std::size_t changes = 0;
  for (std::uint32_t c = 0; c < file_.cell_count(); ++c)
    for (std::uint32_t n : bake_.cells[c].neighbours)
      if (n != rt::kNoCell) {
        check(c, n);
        changes += decoder.entered().size + decoder.left().size;
      }
  EXPECT_GT(changes, 0u);
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::uint32_t> cell(0, file_.cell_count() - 1);
  for (int trial = 0; trial < 200; ++trial) check(cell(rng), cell(rng));
  // Staying in the cell: nothing enters, nothing leaves.
  ASSERT_EQ(decoder.decode_delta(5, 5), rt::Status::kOk);
  EXPECT_EQ(decoder.entered().size, 0u);
  EXPECT_EQ(decoder.left().size, 0u);
  EXPECT_EQ(ids(decoder.view()), bake_.cells[5].pvs);
}

TEST_P(SetOperations, ErrorsLeaveEverythingEmptyAndLaterCallsRight) {
  rt::PvsDecoder decoder(file_, cached());
  const std::uint32_t bad = file_.cell_count();
  const Ids with_bad{3, bad, 4};
  ASSERT_EQ(decoder.decode_delta(3, 4), rt::Status::kOk);
  EXPECT_EQ(decoder.decode_union(with_bad.data(), with_bad.size()), rt::Status::kOutOfRange);
  EXPECT_EQ(decoder.size(), 0u);
  EXPECT_EQ(decoder.entered().size, 0u);
  EXPECT_EQ(decoder.decode_union(nullptr, 2), rt::Status::kInvalidArgument);
  EXPECT_EQ(decoder.size(), 0u);
  EXPECT_EQ(decoder.decode_union(nullptr, 0), rt::Status::kOk);
  EXPECT_EQ(decoder.size(), 0u);
  EXPECT_EQ(decoder.decode_delta(bad, 0), rt::Status::kOutOfRange);
  EXPECT_EQ(decoder.decode_delta(0, bad), rt::Status::kOutOfRange);
  EXPECT_EQ(decoder.size(), 0u);
  EXPECT_EQ(decoder.left().size, 0u);
  // Unions, deltas and single decodes in any order share the decoder's storage.
  const Ids pair{10, 11};
  ASSERT_EQ(decoder.decode_union(pair.data(), pair.size()), rt::Status::kOk);
  EXPECT_EQ(ids(decoder.view()), reference_union(bake_, pair));
  ASSERT_EQ(decoder.decode(12), rt::Status::kOk);
  EXPECT_EQ(ids(decoder.view()), bake_.cells[12].pvs);
  EXPECT_EQ(decoder.entered().size, 0u);
  ASSERT_EQ(decoder.decode_union(pair.data(), pair.size()), rt::Status::kOk);
  EXPECT_EQ(ids(decoder.view()), reference_union(bake_, pair));
}

TEST_P(SetOperations, ACrowdQueriedInTurnGetsEveryCellsOwnList) {
  rt::PvsDecoder decoder(file_, cached());
  ASSERT_GE(decoder.cached_cells(), std::max<std::size_t>(cached(), 1));
  // 40 agents walking the neighbour graph, one decoder asked for each in turn: cells come back
  // from the cache, are decoded in full, or merged against a cached reference.
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::uint32_t> cell(0, file_.cell_count() - 1);
  Ids agents(40);
  for (std::uint32_t& a : agents) a = cell(rng);
  for (int step = 0; step < 60; ++step)
    for (std::uint32_t& a : agents) {
      if (rng() % 4 == 0) {  // crosses into a neighbour now and then
        const std::uint32_t n = bake_.cells[a].neighbours[rng() % 3];
        if (n != rt::kNoCell) a = n;
      }
      ASSERT_EQ(decoder.decode(a), rt::Status::kOk);
      ASSERT_EQ(ids(decoder.view()), bake_.cells[a].pvs) << "cell " << a << ", step " << step;
    }
  // Each diff right after its reference: the merge against the reference's slot wherever the
  // cache has two or more.
  std::size_t diffs = 0;
  for (std::uint32_t c = 0; c < file_.cell_count(); ++c) {
    rt::PvsEncodingInfo info;
    ASSERT_EQ(file_.pvs_encoding(c, info), rt::Status::kOk);
    if (info.reference == rt::kNoCell) continue;
    ++diffs;
    ASSERT_EQ(decoder.decode(info.reference), rt::Status::kOk);
    ASSERT_EQ(ids(decoder.view()), bake_.cells[info.reference].pvs);
    ASSERT_EQ(decoder.decode(c), rt::Status::kOk);
    ASSERT_EQ(ids(decoder.view()), bake_.cells[c].pvs) << "cell " << c;
  }
  EXPECT_EQ(diffs > 0, std::get<0>(GetParam()) > 0);
  EXPECT_EQ(decoder.decode(file_.cell_count()), rt::Status::kOutOfRange);
  EXPECT_EQ(decoder.size(), 0u);
}

// 0: every PVS stored in full; 4: chains of diffs against neighbouring cells.
INSTANTIATE_TEST_SUITE_P(ChainsAndCaches, SetOperations,
                         ::testing::Combine(::testing::Values(0u, 4u),
                                            ::testing::Values(std::size_t{1}, std::size_t{3},
                                                              std::size_t{20}, std::size_t{64})));

}  // namespace
