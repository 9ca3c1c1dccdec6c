// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "urbanpvs/runtime/Crc32c.hpp"

namespace {

using urbanpvs::runtime::crc32c;

/// Bit-at-a-time reference straight from the definition.
std::uint32_t reference_crc32c(const unsigned char* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ ((c & 1u) ? 0x82F63B78u : 0u);
  }
  return ~c;
}

TEST(Crc32c, KnownVectors) {
  const std::string check = "123456789";
  EXPECT_EQ(crc32c(check.data(), check.size()), 0xE3069283u);
  EXPECT_EQ(crc32c(nullptr, 0), 0u);
  // RFC 3720 (iSCSI), appendix B.4.
  std::vector<unsigned char> zeros(32, 0), ones(32, 0xFF), up(32), down(32);
  for (int i = 0; i < 32; ++i) {
    up[i] = static_cast<unsigned char>(i);
    down[i] = static_cast<unsigned char>(31 - i);
  }
  EXPECT_EQ(crc32c(zeros.data(), 32), 0x8A9136AAu);
  EXPECT_EQ(crc32c(ones.data(), 32), 0x62A8AB43u);
  EXPECT_EQ(crc32c(up.data(), 32), 0x46DD794Eu);
  EXPECT_EQ(crc32c(down.data(), 32), 0x113FDB5Cu);
}

TEST(Crc32c, MatchesBitwiseReferenceAtEveryLengthAndAlignment) {
  std::mt19937 rng(3);
  std::vector<unsigned char> data(300);
  for (auto& b : data) b = static_cast<unsigned char>(rng());
  for (std::size_t start = 0; start < 9; ++start) {
    for (std::size_t n = 0; start + n <= data.size(); n += 7) {
      ASSERT_EQ(crc32c(data.data() + start, n), reference_crc32c(data.data() + start, n))
          << start << " " << n;
    }
  }
}

TEST(Crc32c, PortableAndDispatchedPathsAgree) {
  // crc32c() takes the CPU instruction where there is one; the tables must give the same bits.
  std::mt19937 rng(11);
  std::vector<unsigned char> data(1000);
  for (auto& b : data) b = static_cast<unsigned char>(rng());
  for (std::size_t start = 0; start < 9; ++start) {
    for (std::size_t n = 0; start + n <= data.size(); n += 13) {
      const std::uint32_t seed = static_cast<std::uint32_t>(rng());
      ASSERT_EQ(crc32c(data.data() + start, n, seed),
                urbanpvs::runtime::detail::crc32c_portable(data.data() + start, n, seed))
          << start << " " << n;
      ASSERT_EQ(urbanpvs::runtime::detail::crc32c_portable(data.data() + start, n),
                reference_crc32c(data.data() + start, n));
    }
  }
  std::printf("crc32c uses %s\n", urbanpvs::runtime::detail::crc32c_is_hardware()
                                      ? "the CPU's CRC-32C instruction"
                                      : "tables (no CRC-32C instruction)");
}

TEST(Crc32c, Continues) {
  const std::string a = "urbanpvs ", b = "section checksums";
  EXPECT_EQ(crc32c(b.data(), b.size(), crc32c(a.data(), a.size())),
            crc32c((a + b).data(), a.size() + b.size()));
}

}  // namespace
