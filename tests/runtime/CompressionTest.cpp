// SPDX-License-Identifier: MIT
// On realistic data (neighbouring cells sharing ~90% of their PVS) the PVS section must stay
// at most a quarter of plain 32-bit id lists. A smaller city than the benchmark's, same density.
#include <gtest/gtest.h>

#include <cstdio>

#include "SyntheticCity.hpp"
#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace {

namespace rt = urbanpvs::runtime;

std::uint64_t pvs_section_bytes(const rt::PvsFile& file) {
  for (std::size_t i = 0; i < file.section_count(); ++i) {
    if (file.section(i).id == static_cast<std::uint32_t>(rt::format::SectionId::kPvs)) {
      return file.section(i).length;
    }
  }
  return 0;
}

TEST(Compression, RealisticCityIsAtMostAQuarterOfPlainLists) {
  urbanpvs::test::SyntheticCityOptions city;
  city.extent_m = 1200;
  city.squares = 56;  // 6,272 cells
  city.objects = 3200;
  const rt::PvsBake bake = urbanpvs::test::synthetic_city(city);
  for (std::uint32_t chain : {0u, 1u, 4u}) {
    rt::EncodeOptions options;
    options.max_diff_chain = chain;
    const auto bytes = rt::encode(bake, options);
    rt::PvsFile file;
    ASSERT_EQ(rt::PvsFile::open(bytes.data(), bytes.size(), file), rt::Status::kOk);
    const double plain = 4.0 * static_cast<double>(file.total_pvs_entries());
    const double ratio = static_cast<double>(pvs_section_bytes(file)) / plain;
    std::printf("chain %u: %.1f bytes/cell, plain %.1f, ratio %.3f, mean |PVS| %.1f\n", chain,
                static_cast<double>(pvs_section_bytes(file)) / file.cell_count(),
                plain / file.cell_count(), ratio,
                static_cast<double>(file.total_pvs_entries()) / file.cell_count());
    if (chain > 0) {
      EXPECT_LE(ratio, 0.25);
    }
    rt::PvsDecoder decoder(file);
    for (std::uint32_t c = 0; c < file.cell_count(); c += 7) {
      ASSERT_EQ(decoder.decode(c), rt::Status::kOk);
      ASSERT_EQ(std::vector<std::uint32_t>(decoder.begin(), decoder.end()), bake.cells[c].pvs);
    }
  }
}

}  // namespace
