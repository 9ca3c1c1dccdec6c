// SPDX-License-Identifier: GPL-3.0-or-later
// Geographic input: the preprocessor's local frame (LocalFrameMapping, GeographicLib) and the
// runtime's (PvsFile::geodetic_to_local, closed formulas) put a WGS84 point at the same place,
// and both keep verticals vertical, so a 3D model's walls stay walls in plan.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <string>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace {

using namespace urbanpvs;

TEST(GeographicFrame, PreprocessorAndRuntimeMapAlikeAndKeepVerticals) {
  geometry::LocalFrame frame;
  frame.kind = geometry::LocalFrame::Kind::Geographic;
  frame.crs = "OGC:CRS84";
  frame.origin_lat = 35.68;
  frame.origin_lon = 139.76;
  const geometry::LocalFrameMapping mapping(frame);

  runtime::PvsBake bake;
  bake.meta.frame.crs = frame.crs;
  bake.meta.frame.geographic = true;
  bake.meta.frame.geodetic_origin = {frame.origin_lat, frame.origin_lon, 0};
  bake.objects.push_back({});
  runtime::CellRecord cell;
  cell.triangle = {runtime::Point2{0, 0}, runtime::Point2{1, 0}, runtime::Point2{0, 1}};
  cell.z_max = 1;
  cell.pvs = {0};
  bake.cells.push_back(cell);
  const std::vector<std::byte> bytes = runtime::encode(bake);
  runtime::PvsFile file;
  ASSERT_EQ(runtime::PvsFile::open(bytes.data(), bytes.size(), file), runtime::Status::kOk);

  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> d(-0.03, 0.03), h(-50, 600);  // ±3 km, towers
  for (int i = 0; i < 1000; ++i) {
    const double lat = frame.origin_lat + d(rng), lon = frame.origin_lon + d(rng), z = h(rng);
    const geometry::Vec3 baked = mapping.to_local(lon, lat, z);
    std::array<double, 3> run{};
    ASSERT_EQ(file.geodetic_to_local(lat, lon, z, run), runtime::Status::kOk);
    ASSERT_NEAR(baked.x, run[0], 1e-6);
    ASSERT_NEAR(baked.y, run[1], 1e-6);
    ASSERT_NEAR(baked.z, run[2], 1e-9);
    // A wall's top lies exactly above its foot (a tangent plane's plumb lines would spread by
    // z·d/R: 28 cm for a 600 m tower 3 km out).
    const geometry::Vec3 foot = mapping.to_local(lon, lat, 0);
    ASSERT_EQ(baked.x, foot.x);
    ASSERT_EQ(baked.y, foot.y);
    // And back, to well under a millimetre.
    const geometry::Vec3 back = mapping.to_input(baked.x, baked.y, baked.z);
    ASSERT_NEAR(back.x, lon, 1e-8);
    ASSERT_NEAR(back.y, lat, 1e-8);
    ASSERT_EQ(back.z, z);
  }
}

}  // namespace
