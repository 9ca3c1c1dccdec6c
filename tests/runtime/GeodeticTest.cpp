// SPDX-License-Identifier: MIT
// The runtime's closed-form WGS84 → ENU conversion against GeographicLib::LocalCartesian.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "RandomBake.hpp"
#include "urbanpvs/runtime/GeodeticFrame.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

#ifdef URBANPVS_HAVE_GEOGRAPHICLIB
#include <GeographicLib/LocalCartesian.hpp>
#endif

namespace {

namespace rt = urbanpvs::runtime;

TEST(Geodetic, EcefOfKnownPoints) {
  const auto equator = rt::geodetic_to_ecef(0, 0, 0);
  EXPECT_DOUBLE_EQ(equator[0], rt::kWgs84A);
  EXPECT_EQ(equator[1], 0.0);
  EXPECT_EQ(equator[2], 0.0);
  const auto pole = rt::geodetic_to_ecef(90, 0, 0);
  EXPECT_NEAR(pole[2], 6356752.314245179, 1e-6);  // semi-minor axis
  EXPECT_EQ(pole[0], 0.0);
  const rt::GeodeticFrame frame(rt::GeodeticOrigin{52.0, 4.36, 0});
  const auto origin = frame.forward(52.0, 4.36, 0);
  EXPECT_NEAR(origin[0], 0, 1e-9);
  EXPECT_NEAR(origin[1], 0, 1e-9);
  EXPECT_NEAR(origin[2], 0, 1e-9);
  EXPECT_NEAR(frame.forward(52.0, 4.36, 10)[2], 10, 1e-9);
}

#ifdef URBANPVS_HAVE_GEOGRAPHICLIB
TEST(Geodetic, MatchesGeographicLibLocalCartesian) {
  const rt::GeodeticOrigin origins[] = {{52.0116, 4.3571, -1.2},
                                        {47.3769, 8.5417, 408},
                                        {60.1699, 24.9384, 15},
                                        {-33.8688, 151.2093, 3},
                                        {0, 0, 0},
                                        {0.5, 179.99, 100},
                                        {-89.5, -45, 2800},
                                        {89.9, 120, 0},
                                        {35.6762, 139.6503, 40},
                                        {-22.9068, -43.1729, 11}};
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> d(-0.45, 0.45), h(-100, 3000);
  for (const auto& o : origins) {
    const rt::GeodeticFrame mine(o);
    const GeographicLib::LocalCartesian reference(o.lat_deg, o.lon_deg, o.h_m);
    for (int i = 0; i < 2000; ++i) {  // points up to ~50 km away
      const double lat = std::clamp(o.lat_deg + d(rng), -90.0, 90.0);
      const double lon = o.lon_deg + d(rng);
      const double alt = h(rng);
      double x, y, z;
      reference.Forward(lat, lon, alt, x, y, z);
      const auto p = mine.forward(lat, lon, alt);
      ASSERT_NEAR(p[0], x, 1e-6) << lat << " " << lon;
      ASSERT_NEAR(p[1], y, 1e-6) << lat << " " << lon;
      ASSERT_NEAR(p[2], z, 1e-6) << lat << " " << lon;
    }
  }
}
#else
TEST(Geodetic, MatchesGeographicLibLocalCartesian) {
  GTEST_SKIP() << "GeographicLib not found at configure time";
}
#endif

TEST(Geodetic, FileConvertsThroughItsFrame) {
  rt::PvsBake bake = urbanpvs::test::random_mesh_bake(4, {});
  bake.meta.frame = {"EPSG:4326", true, {52.0116, 4.3571, 0.0}, {10.0, -20.0, 1.0}};
  const auto bytes = rt::encode(bake);
  rt::PvsFile file;
  ASSERT_EQ(rt::PvsFile::open(bytes.data(), bytes.size(), file), rt::Status::kOk);
  std::array<double, 3> local{};
  ASSERT_EQ(file.geodetic_to_local(52.0116, 4.3571, 5.0, local), rt::Status::kOk);
  EXPECT_NEAR(local[0], -10.0, 1e-9);  // ENU (0, 0, 5) minus the origin
  EXPECT_NEAR(local[1], 20.0, 1e-9);
  EXPECT_NEAR(local[2], 4.0, 1e-9);

  const rt::PvsBake projected = urbanpvs::test::random_mesh_bake(4, {});
  const auto projected_bytes = rt::encode(projected);
  rt::PvsFile other;
  ASSERT_EQ(rt::PvsFile::open(projected_bytes.data(), projected_bytes.size(), other),
            rt::Status::kOk);
  EXPECT_EQ(other.geodetic_to_local(52, 4, 0, local), rt::Status::kNotGeographic);
  const auto in = other.local_to_input(1, 2, 3);
  EXPECT_EQ(other.input_to_local(in[0], in[1], in[2]), (std::array<double, 3>{1, 2, 3}));
}

}  // namespace
