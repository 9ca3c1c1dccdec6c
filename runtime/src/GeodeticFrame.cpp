// SPDX-License-Identifier: MIT
#include "urbanpvs/runtime/GeodeticFrame.hpp"

#include <cmath>

namespace urbanpvs::runtime {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kE2 = kWgs84F * (2 - kWgs84F);  // first eccentricity squared

/// sin and cos of an angle in degrees, reduced to [-45, 45] degrees first so that multiples of
/// 90 degrees come out exact (as GeographicLib's sincosd does): cos(90°) is 0, not 6e-17.
void sincos_deg(double deg, double& s, double& c) noexcept {
  double r = std::fmod(deg, 360.0);
  const double q = std::round(r / 90.0);  // quadrant
  r -= 90.0 * q;
  const double rad = r * (kPi / 180.0);
  const double sr = std::sin(rad), cr = std::cos(rad);
  switch (static_cast<int>(std::fmod(q + 4.0, 4.0))) {
    case 0:
      s = sr;
      c = cr;
      break;
    case 1:
      s = cr;
      c = -sr;
      break;
    case 2:
      s = -sr;
      c = -cr;
      break;
    default:
      s = -cr;
      c = sr;
      break;
  }
  s += 0.0;  // turn -0 into +0
  c += 0.0;
}

}  // namespace

std::array<double, 3> geodetic_to_ecef(double lat_deg, double lon_deg, double h_m) noexcept {
  double sin_lat, cos_lat, sin_lon, cos_lon;
  sincos_deg(lat_deg, sin_lat, cos_lat);
  sincos_deg(lon_deg, sin_lon, cos_lon);
  // Prime vertical radius of curvature.
  const double n = kWgs84A / std::sqrt(1 - kE2 * sin_lat * sin_lat);
  return {(n + h_m) * cos_lat * cos_lon, (n + h_m) * cos_lat * sin_lon,
          (n * (1 - kE2) + h_m) * sin_lat};
}

GeodeticFrame::GeodeticFrame(const GeodeticOrigin& origin) noexcept
    : origin_(origin), origin_ecef_(geodetic_to_ecef(origin.lat_deg, origin.lon_deg, origin.h_m)) {
  double sin_lat, cos_lat, sin_lon, cos_lon;
  sincos_deg(origin.lat_deg, sin_lat, cos_lat);
  sincos_deg(origin.lon_deg, sin_lon, cos_lon);
  rotation_ = {-sin_lon,
               cos_lon,
               0,  // east
               -sin_lat * cos_lon,
               -sin_lat * sin_lon,
               cos_lat,  // north
               cos_lat * cos_lon,
               cos_lat * sin_lon,
               sin_lat};  // up
}

std::array<double, 3> GeodeticFrame::forward(double lat_deg, double lon_deg,
                                             double h_m) const noexcept {
  const std::array<double, 3> p = geodetic_to_ecef(lat_deg, lon_deg, h_m);
  const double dx = p[0] - origin_ecef_[0];
  const double dy = p[1] - origin_ecef_[1];
  const double dz = p[2] - origin_ecef_[2];
  const auto& r = rotation_;
  return {r[0] * dx + r[1] * dy + r[2] * dz, r[3] * dx + r[4] * dy + r[5] * dz,
          r[6] * dx + r[7] * dy + r[8] * dz};
}

}  // namespace urbanpvs::runtime
