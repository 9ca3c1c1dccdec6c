// SPDX-License-Identifier: MIT
// White-box tests of the encoding primitives: varints, exp-Golomb codes, diff references, grid
// mapping, the triangle predicate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "ExpGolomb.hpp"
#include "PointLocationGrid.hpp"
#include "PvsCodec.hpp"
#include "urbanpvs/runtime/Types.hpp"

namespace {

namespace rt = urbanpvs::runtime;
namespace detail = urbanpvs::runtime::detail;

bool decode(const std::vector<unsigned char>& bytes, std::uint32_t& v) {
  const unsigned char* p = bytes.data();
  return detail::read_varint(p, bytes.data() + bytes.size(), v) && p == bytes.data() + bytes.size();
}

TEST(Varint, RoundTripsBoundaryValues) {
  for (std::uint32_t v : {0u, 1u, 127u, 128u, 255u, 16383u, 16384u, 2097151u, 2097152u, 268435455u,
                          268435456u, 0xFFFFFFFEu, 0xFFFFFFFFu}) {
    std::vector<unsigned char> bytes;
    detail::append_varint(bytes, v);
    EXPECT_EQ(bytes.size(), detail::varint_size(v));
    std::uint32_t back = 0;
    ASSERT_TRUE(decode(bytes, back)) << v;
    EXPECT_EQ(back, v);
  }
}

TEST(Varint, RejectsTruncatedOverlongAndOversized) {
  std::uint32_t v;
  EXPECT_FALSE(decode({}, v));
  EXPECT_FALSE(decode({0x80}, v));                                // truncated
  EXPECT_FALSE(decode({0x80, 0x00}, v));                          // non-minimal zero
  EXPECT_FALSE(decode({0xFF, 0x80, 0x00}, v));                    // non-minimal
  EXPECT_FALSE(decode({0xFF, 0xFF, 0xFF, 0xFF, 0x10}, v));        // 2^32
  EXPECT_FALSE(decode({0xFF, 0xFF, 0xFF, 0xFF, 0x8F, 0x01}, v));  // six bytes
  EXPECT_TRUE(decode({0xFF, 0xFF, 0xFF, 0xFF, 0x0F}, v));
  EXPECT_EQ(v, 0xFFFFFFFFu);
}

TEST(ExpGolomb, RoundTripsEveryOrderAndBoundaryGap) {
  const std::uint64_t gaps[] = {
      0, 1, 2, 3, 7, 8, 127, 128, 65535, 0xFFFFFFFFu, 0x1FFFFFFFFull - 0x80000000ull};
  for (unsigned k = 0; k <= detail::kMaxExpGolombOrder; ++k) {
    std::vector<unsigned char> bytes;
    std::uint64_t bits = 0;
    {
      detail::BitWriter w(bytes);
      for (std::uint64_t g : gaps) {
        if (g + (std::uint64_t{1} << k) >= (std::uint64_t{1} << 33)) continue;
        w.code(g, k);
        bits += detail::exp_golomb_bits(g, k);
      }
    }
    EXPECT_EQ(bytes.size(), (bits + 7) / 8) << "k " << k;
    detail::BitReader r(bytes.data(), bytes.size());
    for (std::uint64_t g : gaps) {
      if (g + (std::uint64_t{1} << k) >= (std::uint64_t{1} << 33)) continue;
      std::uint64_t back = 0;
      ASSERT_TRUE(r.code(k, back)) << "k " << k << " gap " << g;
      EXPECT_EQ(back, g);
    }
    EXPECT_EQ(r.position(), bits);
    EXPECT_TRUE(r.at_padded_end());
    std::uint64_t more;
    EXPECT_FALSE(r.code(k, more));  // nothing but padding left
  }
  // Code lengths: 1 bit for a gap of 0 with order 0, 2n - k - 1 in general.
  EXPECT_EQ(detail::exp_golomb_bits(0, 0), 1u);
  EXPECT_EQ(detail::exp_golomb_bits(1, 0), 3u);
  EXPECT_EQ(detail::exp_golomb_bits(0, 3), 4u);
  EXPECT_EQ(detail::exp_golomb_bits(8, 3), 6u);
}

TEST(ExpGolomb, ReaderNeverReadsPastItsBytes) {
  std::vector<unsigned char> bytes;
  {
    detail::BitWriter w(bytes);
    w.code(1000, 2);
  }
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    // A copy of exactly `cut` bytes on the heap: ASan sees any read past it.
    std::unique_ptr<unsigned char[]> prefix(new unsigned char[std::max<std::size_t>(cut, 1)]);
    std::copy(bytes.begin(), bytes.begin() + static_cast<long>(cut), prefix.get());
    detail::BitReader r(prefix.get(), cut);
    std::uint64_t g;
    EXPECT_FALSE(r.code(2, g)) << cut;
  }
  // 64 zero bits and more: no code.
  const std::vector<unsigned char> zeros(16, 0);
  detail::BitReader r(zeros.data(), zeros.size());
  std::uint64_t g;
  EXPECT_FALSE(r.code(0, g));
}

// The code as ExpGolomb.hpp defines it, read one bit at a time: the reference the reader's
// windowed decoding must agree with, value for value and failure for failure.
class BitByBitReader {
 public:
  BitByBitReader(const unsigned char* data, std::size_t size) : data_(data), bits_(size * 8) {}
  std::uint64_t position() const { return position_; }
  bool code(unsigned k, std::uint64_t& gap) {
    std::uint64_t at = position_;
    unsigned zeros = 0;
    for (;; ++zeros) {
      if (at >= bits_ || zeros + k > 32) return false;  // past the end, or v >= 2^34
      if (bit(at++)) break;
    }
    const unsigned low = zeros + k;
    if (at + low > bits_) return false;
    std::uint64_t v = std::uint64_t{1} << low;
    for (unsigned i = 0; i < low; ++i) v |= std::uint64_t{bit(at + i)} << i;
    position_ = at + low;
    gap = v - (std::uint64_t{1} << k);
    return true;
  }

 private:
  unsigned bit(std::uint64_t at) const { return (data_[at / 8] >> (at % 8)) & 1u; }
  const unsigned char* data_;
  std::uint64_t bits_;
  std::uint64_t position_ = 0;
};

TEST(ExpGolomb, ReaderAgreesWithABitByBitDecoderOnAnyBytes) {
  // Random bytes: dense ones give runs of short codes (the reader's fast path, across the ends
  // of its window), sparse ones long codes and codes that fail; the reader may look at bytes
  // past the stream (readable > size) but a code ending there must fail as it does here.
  std::mt19937_64 rng(29);
  std::uint64_t codes = 0, failures = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const std::size_t size = rng() % 48;
    const std::size_t readable = size + (trial % 2 == 0 ? 0 : rng() % 12);
    const unsigned density = 1 + static_cast<unsigned>(rng() % 8);  // ones per 8 bits, about
    std::unique_ptr<unsigned char[]> bytes(new unsigned char[std::max<std::size_t>(readable, 1)]);
    for (std::size_t i = 0; i < readable; ++i) {
      unsigned b = 0;
      for (unsigned j = 0; j < 8; ++j) b |= (rng() % 8 < density ? 1u : 0u) << j;
      bytes[i] = static_cast<unsigned char>(b);
    }
    detail::BitReader reader(bytes.get(), size, readable);
    BitByBitReader reference(bytes.get(), size);
    for (;;) {
      // Mostly small orders, as the writer picks; now and then one up to the largest.
      const unsigned k =
          rng() % 16 == 0 ? static_cast<unsigned>(rng() % 32) : static_cast<unsigned>(rng() % 4);
      std::uint64_t got = 0, want = 0;
      const bool ok = reader.code(k, got);
      ASSERT_EQ(ok, reference.code(k, want)) << "trial " << trial << " bit " << reader.position();
      if (!ok) {
        ++failures;
        break;
      }
      ++codes;
      ASSERT_EQ(got, want) << "trial " << trial;
      ASSERT_EQ(reader.position(), reference.position()) << "trial " << trial;
    }
  }
  EXPECT_GT(codes, 50000u);  // the fast path was exercised, and failures too
  EXPECT_EQ(failures, 4000u);
}

TEST(ExpGolomb, BestOrderReportsItsOwnSize) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<std::uint32_t> values;
    const std::uint32_t spread = 1u << (rng() % 20);
    for (std::uint32_t v = rng() % spread; values.size() < 1 + rng() % 200; v += 1 + rng() % spread)
      values.push_back(v);
    std::uint64_t bits = 0;
    const unsigned k = detail::best_exp_golomb_order(values, 7, bits);
    ASSERT_LE(k, 7u);
    std::uint64_t want = 0, base = 0;
    for (std::uint32_t v : values) {
      want += detail::exp_golomb_bits(v - base, k);
      base = std::uint64_t{v} + 1;
    }
    EXPECT_EQ(bits, want);
    // No order within [0, 7] is more than a bit per value better than the one chosen.
    for (unsigned other = 0; other <= 7; ++other) {
      std::uint64_t b = 0;
      base = 0;
      for (std::uint32_t v : values) {
        b += detail::exp_golomb_bits(v - base, other);
        base = std::uint64_t{v} + 1;
      }
      EXPECT_LE(bits, b + values.size()) << "trial " << trial << " k " << k << " vs " << other;
    }
  }
}

TEST(DiffReference, ZigzagIsABijectionAndSmallForNeighbours) {
  for (std::uint32_t cell : {0u, 1u, 1000u, 0xFFFFFFFEu}) {
    for (std::uint32_t ref : {0u, 1u, 999u, 1001u, 0x7FFFFFFFu, 0xFFFFFFFEu}) {
      EXPECT_EQ(detail::decode_reference(cell, detail::encode_reference(cell, ref)), ref);
    }
  }
  EXPECT_EQ(detail::encode_reference(1000, 999), 1u);
  EXPECT_EQ(detail::encode_reference(1000, 1001), 2u);
}

TEST(Grid, CoordinateMappingIsMonotonicAndClamped) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> v(-100, 1100);
  for (int i = 0; i < 10000; ++i) {
    double a = v(rng), b = v(rng);
    if (a > b) std::swap(a, b);
    EXPECT_LE(detail::grid_coordinate(a, 0, 7.3, 137), detail::grid_coordinate(b, 0, 7.3, 137));
  }
  EXPECT_EQ(detail::grid_coordinate(-1e300, 0, 1, 10), 0u);
  EXPECT_EQ(detail::grid_coordinate(1e300, 0, 1, 10), 9u);
  EXPECT_EQ(detail::grid_coordinate(std::numeric_limits<double>::infinity(), 0, 1, 10), 9u);
  EXPECT_EQ(detail::grid_coordinate(std::nan(""), 0, 1, 10), 0u);
}

TEST(Triangle, ClosedOnEdgesAndVerticesEitherOrientation) {
  const std::array<rt::Point2, 3> ccw{{{0, 0}, {4, 0}, {0, 4}}};
  const std::array<rt::Point2, 3> cw{{{0, 0}, {0, 4}, {4, 0}}};
  for (const auto& t : {ccw, cw}) {
    EXPECT_TRUE(rt::triangle_contains(t, 1, 1));
    EXPECT_TRUE(rt::triangle_contains(t, 0, 0));  // vertex
    EXPECT_TRUE(rt::triangle_contains(t, 2, 0));  // edge
    EXPECT_TRUE(rt::triangle_contains(t, 2, 2));  // hypotenuse
    EXPECT_FALSE(rt::triangle_contains(t, 2.0001, 2));
    EXPECT_FALSE(rt::triangle_contains(t, -0.0001, 1));
  }
  const std::array<rt::Point2, 3> degenerate{{{0, 0}, {1, 1}, {2, 2}}};
  EXPECT_FALSE(rt::triangle_contains(degenerate, 1, 1));
}

TEST(Triangle, SharedEdgesLeaveNoCracks) {
  // Two triangles sharing a long skew edge: every point sampled on or near the edge is in at
  // least one of them.
  const rt::Point2 a{0.1, 0.3}, b{1000.7, 733.9}, c{0, 800}, d{900, 0};
  const std::array<rt::Point2, 3> left{{a, b, c}}, right{{b, a, d}};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> t(0.01, 0.99), e(-1e-12, 1e-12);
  for (int i = 0; i < 100000; ++i) {
    const double s = t(rng);
    const double x = a.x + s * (b.x - a.x) + e(rng) * 1000, y = a.y + s * (b.y - a.y);
    ASSERT_TRUE(rt::triangle_contains(left, x, y) || rt::triangle_contains(right, x, y))
        << x << " " << y;
  }
}

}  // namespace

namespace {

/// The lists of a diff payload: removed positions, then added ids, each gap-coded as FORMAT.md
/// describes kind 2 (varints, or exp-Golomb codes of orders kr and ka in one bit stream when
/// `coded`) — written here, not by the encoder, so that invalid diffs (collisions, positions
/// past the reference) can be built too.
std::vector<unsigned char> diff_lists(const std::vector<std::uint32_t>& removed,
                                      const std::vector<std::uint32_t>& added, bool coded,
                                      unsigned kr, unsigned ka) {
  std::vector<unsigned char> out;
  detail::BitWriter bits(out);
  for (const auto* list : {&removed, &added}) {
    std::uint64_t base = 0;
    for (std::uint32_t v : *list) {
      if (coded) {
        bits.code(v - base, list == &removed ? kr : ka);
      } else {
        detail::append_varint(out, static_cast<std::uint32_t>(v - base));
      }
      base = std::uint64_t{v} + 1;
    }
  }
  bits.flush();
  return out;
}

/// check_diff must accept exactly the diffs whose merge gives a strictly increasing list of the
/// declared size in range — it stands in for decoding them at load.
TEST(CheckDiff, AgreesWithMergeAndTheAscendingCheck) {
  std::mt19937 rng(5);
  const std::uint32_t objects = 64;
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<std::uint32_t> ref;
    for (std::uint32_t o = 0; o < objects; ++o)
      if (rng() % 3 == 0) ref.push_back(o);
    // Removed positions and added ids, strictly increasing; sometimes past the reference or an
    // id already kept (a collision), sometimes an id out of range.
    std::vector<std::uint32_t> removed, added;
    for (std::uint32_t p = 0; p < ref.size() + 2; ++p)
      if (rng() % 8 == 0) removed.push_back(p);
    for (std::uint32_t o = 0; o < objects + 2; ++o) {
      const bool kept = std::binary_search(ref.begin(), ref.end(), o);
      if (rng() % (kept ? 40 : 10) == 0) added.push_back(o);
    }
    const std::uint64_t expected_size = ref.size() + added.size() - removed.size();
    const std::uint32_t declared =
        static_cast<std::uint32_t>(expected_size + (rng() % 10 == 0 ? 1 : 0));
    const bool coded = trial % 2 == 1;
    const unsigned kr = rng() % 4, ka = rng() % 4;
    const std::vector<unsigned char> lists = diff_lists(removed, added, coded, kr, ka);
    detail::DiffHeader d{};
    d.coded = coded;
    d.removed_order = static_cast<std::uint8_t>(kr);
    d.added_order = static_cast<std::uint8_t>(ka);
    d.removed = static_cast<std::uint32_t>(removed.size());
    d.added = static_cast<std::uint32_t>(added.size());
    d.lists = lists.data();
    d.end = lists.data() + lists.size();
    d.blob_end = d.end;
    std::vector<std::uint32_t> out(ref.size() + added.size() + 4);
    std::size_t n = 0;
    bool want = detail::merge_decoded(d, ref.data(), ref.size(), out.data(), out.size(), n) &&
                n == declared;
    for (std::size_t i = 0; want && i < n; ++i)
      want = out[i] < objects && (i == 0 || out[i] > out[i - 1]);
    // Scratch of the reference's size, the load's (a removal past the reference is refused
    // before it would need more).
    std::vector<std::uint32_t> scratch(ref.size());
    ASSERT_EQ(detail::check_diff(d, declared, ref.data(), ref.size(), objects, scratch.data(),
                                 scratch.size()),
              want)
        << "trial " << trial;
    (want ? accepted : refused)++;
  }
  // Both outcomes are common, so the comparison means something.
  EXPECT_GT(accepted, 1000);
  EXPECT_GT(refused, 1000);
}

}  // namespace
