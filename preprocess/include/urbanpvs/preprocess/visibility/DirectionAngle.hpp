// SPDX-License-Identifier: GPL-3.0-or-later
// The direction of a vector as an angle, for the sample horizons' sectors (SampleHorizon,
// thesis 5.6). glibc's atan2 is correctly rounded, and it pays for that with a switch of the
// rounding mode on every call: 15 % of a far-field sweep's time went to atan2 in `perf`, 40 % of
// that to the switch. The horizons need far less: every angle they use is widened or narrowed by
// 1e-9 rad (kAngleSlack in SampleHorizon.cpp) before it picks a sector, so an angle within
// 1e-15 rad of the true one picks the same sectors as a correctly rounded one.
#pragma once

#include <cmath>
#include <numbers>

namespace urbanpvs::preprocess {

namespace detail {

// atan(n / d) for 0 <= n <= d, d > 0. The range of n / d is cut at tan(π/24), tan(3π/24) and
// tan(5π/24) into pieces around c = 0, π/12, π/6 and π/4, and atan(n / d) = c + atan(t) with
// t = (n − d·tan c) / (d + n·tan c) (one division), so that |t| <= tan(π/24) < 0.1317. There the
// series t − t³/3 + t⁵/5 − … to t¹⁵ leaves out less than 0.1317¹⁷/17 < 1e-16. No branch: the
// horizons ask for directions all round, which no branch predictor guesses.
inline double atan_of_ratio(double n, double d) {
  // tan(c) as doubles, and atan of those doubles (c itself to within an ulp).
  constexpr double kTan[4] = {0.0, 0.2679491924311227, 0.5773502691896257, 1.0};
  constexpr double kAtan[4] = {0.0, 0.2617993877991494, 0.5235987755982988, 0.7853981633974483};
  constexpr double kCut[3] = {0.13165249758739583, 0.41421356237309503, 0.7673269879789604};
  const int k = (n >= kCut[0] * d) + (n >= kCut[1] * d) + (n >= kCut[2] * d);
  const double t = (n - kTan[k] * d) / (d + n * kTan[k]);
  const double u = t * t;
  double s = -1.0 / 15;
  s = s * u + 1.0 / 13;
  s = s * u - 1.0 / 11;
  s = s * u + 1.0 / 9;
  s = s * u - 1.0 / 7;
  s = s * u + 1.0 / 5;
  s = s * u - 1.0 / 3;
  return kAtan[k] + (t + t * u * s);
}

}  // namespace detail

/// The angle of (x, y) in [-π, π], as std::atan2(y, x) gives it to within 1e-15 rad, signed
/// zeros included (y = ±0 with x < 0 gives ±π); 0 for (0, 0). Finite arguments only.
inline double direction_angle(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const bool steep = ay > ax;
  const double d = steep ? ay : ax;
  // (0, 0): the angle of (±0, ±0), as atan2 gives it, from 0 / 1.
  double a = detail::atan_of_ratio(steep ? ax : ay, d > 0 ? d : 1.0);
  a = steep ? std::numbers::pi / 2 - a : a;
  a = std::signbit(x) ? std::numbers::pi - a : a;
  return std::copysign(a, y);
}

}  // namespace urbanpvs::preprocess
