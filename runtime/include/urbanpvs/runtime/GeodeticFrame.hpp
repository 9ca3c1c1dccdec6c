// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// WGS84 geodetic coordinates → local east-north-up (ENU) frame, with the closed formulas
/// (geodetic → ECEF → rotation about the origin). Same frame as GeographicLib::LocalCartesian,
/// which the preprocessor uses to bake geographic inputs; tests check agreement to 1e-6 m.

#include <array>

#include "urbanpvs/runtime/Types.hpp"

namespace urbanpvs::runtime {

/// WGS84 ellipsoid.
inline constexpr double kWgs84A = 6378137.0;
inline constexpr double kWgs84F = 1.0 / 298.257223563;

/// Earth-centred, earth-fixed coordinates (m) of a WGS84 point.
std::array<double, 3> geodetic_to_ecef(double lat_deg, double lon_deg, double h_m) noexcept;

/// An east-north-up frame tangent to the ellipsoid at an origin. Immutable, cheap to copy.
class GeodeticFrame {
 public:
  explicit GeodeticFrame(const GeodeticOrigin& origin) noexcept;

  /// ENU coordinates (m): x east, y north, z up, of the WGS84 point.
  std::array<double, 3> forward(double lat_deg, double lon_deg, double h_m) const noexcept;

  const GeodeticOrigin& origin() const noexcept { return origin_; }

 private:
  GeodeticOrigin origin_;
  std::array<double, 3> origin_ecef_{};
  std::array<double, 9> rotation_{};  // rows: east, north, up unit vectors in ECEF
};

}  // namespace urbanpvs::runtime
