// SPDX-License-Identifier: GPL-3.0-or-later
// direction_angle against the C library's correctly rounded atan2: the sample horizons widen or
// narrow every angle by 1e-9 rad (SampleHorizon.cpp), so 1e-15 rad is far inside what they
// tolerate, and what atan2 does with signs and zeros must be kept exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "urbanpvs/preprocess/visibility/DirectionAngle.hpp"

namespace urbanpvs::preprocess {
namespace {

TEST(DirectionAngle, WithinOneFemtoradianOfAtan2AllRound) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> unit(-1, 1);
  double worst = 0;
  for (int i = 0; i < 2'000'000; ++i) {
    // Offsets from a micrometre to a thousand kilometres, every direction.
    const double y = unit(random) * std::pow(10.0, 6 * unit(random) + 3);
    double x = unit(random) * std::pow(10.0, 6 * unit(random) + 3);
    if (i % 5 == 0) x = y * (1 + 1e-12 * unit(random));  // near the diagonals: a piece's seam
    if (i % 7 == 0) x = -x;
    const double error = std::abs(direction_angle(y, x) - std::atan2(y, x));
    worst = std::max(worst, error);
    ASSERT_LE(error, 1e-15) << "y " << y << " x " << x;
  }
  EXPECT_GT(worst, 0.0);  // a different formula, not atan2 itself
}

TEST(DirectionAngle, SeamsOfItsPiecesAndTheAxes) {
  // The cuts between its pieces of [0, π/4] lie at tan(π/24), tan(3π/24), tan(5π/24); each
  // side of each, and the axes and diagonals in all four quadrants.
  for (int k = 0; k <= 24; ++k) {
    const double a = k * std::numbers::pi / 12 - std::numbers::pi;
    for (double d : {-1e-13, 0.0, 1e-13}) {
      const double y = std::sin(a + d), x = std::cos(a + d);
      EXPECT_NEAR(direction_angle(y, x), std::atan2(y, x), 1e-15) << "angle " << a + d;
    }
  }
  for (int k = 1; k <= 5; k += 2) {
    const double t = std::tan(k * std::numbers::pi / 24);
    for (double r : {std::nextafter(t, 0.0), t, std::nextafter(t, 2.0)})
      EXPECT_NEAR(direction_angle(r, 1.0), std::atan2(r, 1.0), 1e-15) << "ratio " << r;
  }
  EXPECT_EQ(direction_angle(1.0, 0.0), std::numbers::pi / 2);
  EXPECT_EQ(direction_angle(-1.0, 0.0), -std::numbers::pi / 2);
  EXPECT_EQ(direction_angle(0.0, -1.0), std::numbers::pi);
  EXPECT_EQ(direction_angle(2.0, 2.0), std::numbers::pi / 4);
}

TEST(DirectionAngle, SignedZerosAsAtan2) {
  for (double y : {0.0, -0.0})
    for (double x : {0.0, -0.0, 1.0, -1.0}) {
      const double ours = direction_angle(y, x), theirs = std::atan2(y, x);
      EXPECT_EQ(ours, theirs) << "y " << y << " x " << x;
      EXPECT_EQ(std::signbit(ours), std::signbit(theirs)) << "y " << y << " x " << x;
    }
}

}  // namespace
}  // namespace urbanpvs::preprocess
