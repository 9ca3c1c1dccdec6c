// SPDX-License-Identifier: GPL-3.0-or-later
// --terrain FILE (DemTerrain.hpp): the TIN resampled from a DEM against what the raster says,
// read without GDAL where possible: the SRTM tiles of ../shared/cities from their own bytes
// (1201 x 1201 big-endian int16 posts), GeoTIFFs written by the test from known planes, and a
// reprojection (lon/lat raster under a UTM city) checked with GeographicLib's UTM, not PROJ.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <GeographicLib/UTMUPS.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <tuple>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/DemTerrain.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"

namespace fs = std::filesystem;
using namespace urbanpvs::geometry;

namespace {

const fs::path kShared = URBANPVS_SHARED_CITIES;

// An SRTM3 tile read from its bytes: posts at whole 1/1200 degrees, row 0 the northern edge.
struct SrtmTile {
  int lon0 = 0, lat0 = 0;
  std::vector<std::int16_t> posts;

  SrtmTile(const fs::path& path, int lon, int lat) : lon0(lon), lat0(lat), posts(1201 * 1201) {
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes(2 * posts.size());
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    EXPECT_TRUE(in) << path;
    for (std::size_t i = 0; i < posts.size(); ++i)
      posts[i] = std::int16_t(std::uint16_t(bytes[2 * i] << 8 | bytes[2 * i + 1]));
  }
  double post(int col, int row) const { return posts[std::size_t(row) * 1201 + col]; }
  static constexpr std::int16_t kVoid = -32768;
  // The bilinear surface through the posts (the raster's own model between pixel centres),
  // over the posts that are not voids (SRTM3 has voids on steep slopes).
  double at(double lon, double lat) const {
    const double u = (lon - lon0) * 1200, v = (lat0 + 1 - lat) * 1200;
    const int i = std::min(int(u), 1199), j = std::min(int(v), 1199);
    const double fu = u - i, fv = v - j;
    double sum = 0, weight = 0;
    for (const auto& [w, a, b] :
         {std::tuple{(1 - fu) * (1 - fv), i, j}, std::tuple{fu * (1 - fv), i + 1, j},
          std::tuple{(1 - fu) * fv, i, j + 1}, std::tuple{fu * fv, i + 1, j + 1}})
      if (post(a, b) != kVoid) sum += w * post(a, b), weight += w;
    return weight > 0 ? sum / weight : double(kVoid);
  }
};

// Every vertex of the TIN, once per triangle it belongs to.
void for_each_vertex(const Terrain& t, const std::function<void(const Vec3&)>& f) {
  for (const Triangle3& tri : t.triangles)
    for (const Vec3& v : tri.v) f(v);
}

// A one-band Float32 GeoTIFF of `cols` x `rows` pixels, north up, whose pixel (i, j) centre is
// at (x0 + (i + 0.5) dx, y0 - (j + 0.5) dy) and holds z(x, y), or -9999 (no-data) where
// `void_at` says so.
void write_geotiff(const fs::path& path, const char* crs, double x0, double y0, double dx,
                   double dy, int cols, int rows, const std::function<double(double, double)>& z,
                   const std::function<bool(int, int)>& void_at = {}) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  ASSERT_NE(driver, nullptr);
  GDALDataset* ds = driver->Create(path.c_str(), cols, rows, 1, GDT_Float32, nullptr);
  ASSERT_NE(ds, nullptr);
  double gt[6] = {x0, dx, 0, y0, 0, -dy};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.SetFromUserInput(crs);
  ds->SetSpatialRef(&srs);
  std::vector<float> data(std::size_t(cols) * rows);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i)
      data[std::size_t(j) * cols + i] =
          void_at && void_at(i, j) ? -9999.0f : float(z(x0 + (i + 0.5) * dx, y0 - (j + 0.5) * dy));
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetNoDataValue(-9999);
  ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, cols, rows, data.data(), cols, rows, GDT_Float32, 0, 0),
            CE_None);
  GDALClose(GDALDataset::ToHandle(ds));
}

LocalFrame projected(const char* crs, double x, double y) {
  LocalFrame f;
  f.kind = LocalFrame::Kind::Projected;
  f.crs = crs;
  f.origin = {x, y, 0};
  return f;
}

struct TempDir {
  fs::path path =
      fs::temp_directory_path() /
      ("urbanpvs-dem-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
       ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

}  // namespace

TEST(DemTerrain, SrtmTileOverMonacoIsItsOwnPostsBilinearly) {
  const fs::path hgt = kShared / "dem" / "N43E007.hgt";
  if (!fs::exists(hgt)) GTEST_SKIP() << hgt << " is absent";
  const SrtmTile tile(hgt, 7, 43);
  Box2 lonlat{{7.40, 43.72}, {7.44, 43.76}};
  const LocalFrame frame = choose_local_frame(LocalFrame::Kind::Geographic, "OGC:CRS84", lonlat);
  const LocalFrameMapping mapping(frame);
  Box2 area;
  area.extend(Vec2{-1500, -2000});
  area.extend(Vec2{1500, 2000});
  DemSummary s;
  const Terrain t = read_dem_terrain(hgt, frame, area, &s);
  EXPECT_EQ(s.driver, "SRTMHGT");
  EXPECT_EQ(s.crs, "EPSG:4326");
  EXPECT_NEAR(s.pixel_y, 92.6, 0.2);  // 3" of latitude
  EXPECT_NEAR(s.pixel_x, 67.1, 0.2);  // 3" of longitude at 43.74 N
  EXPECT_EQ(s.filled, 0u);
  EXPECT_EQ(t.triangles.size(), 2u * std::size_t(s.columns - 1) * std::size_t(s.rows - 1));
  double highest = -1e9;
  std::size_t checked = 0;
  for_each_vertex(t, [&](const Vec3& v) {
    const Vec3 in = mapping.to_input(v.x, v.y, 0);
    ASSERT_NEAR(v.z, tile.at(in.x, in.y), 1e-6) << "at lon " << in.x << " lat " << in.y;
    highest = std::max(highest, v.z);
    ++checked;
  });
  EXPECT_GT(checked, 10000u);
  EXPECT_GT(highest, 400);  // the slopes above Monaco, not a flat sea
}

TEST(DemTerrain, GeoTiffInTheCitysCrsWithAVoid) {
  const TempDir dir;
  const fs::path tif = dir.path / "plane.tif";
  // A plane in EPSG:28992 metres, 10 m pixels, with a no-data hole of 6 x 6 pixels.
  auto plane = [](double x, double y) { return 5.0 + 0.01 * (x - 84000) + 0.02 * (y - 447000); };
  write_geotiff(tif, "EPSG:28992", 84000, 448000, 10, 10, 100, 100, plane,
                [](int i, int j) { return i >= 40 && i < 46 && j >= 50 && j < 56; });
  const LocalFrame frame = projected("EPSG:28992", 84100, 447100);
  Box2 area{{0, 0}, {800, 800}};
  DemSummary s;
  const Terrain t = read_dem_terrain(tif, frame, area, &s);
  EXPECT_EQ(s.driver, "GTiff");
  EXPECT_NEAR(s.spacing, 5, 1e-9);  // half the raster's pixel
  EXPECT_GT(s.filled, 0u);          // the hole's inside had no usable pixel
  const Box2 hole{{84000 + 400 - 10, 448000 - 560 - 10}, {84000 + 460 + 10, 448000 - 500 + 10}};
  double lo = 1e9, hi = -1e9;
  // The plane over the pixels whose centres lie around the box (one pixel beyond the hole).
  for (int j = 48; j <= 57; ++j)
    for (int i = 38; i <= 47; ++i) {
      const double z = plane(84000 + (i + 0.5) * 10, 448000 - (j + 0.5) * 10);
      lo = std::min(lo, z), hi = std::max(hi, z);
    }
  for_each_vertex(t, [&](const Vec3& v) {
    const double x = v.x + 84100, y = v.y + 447100;
    if (x < hole.min.x || x > hole.max.x || y < hole.min.y || y > hole.max.y)
      ASSERT_NEAR(v.z, plane(x, y), 1e-3) << x << " " << y;  // float pixels
    else
      ASSERT_TRUE(v.z >= lo - 1e-3 && v.z <= hi + 1e-3)
          << "a filled void leaves its rim's range: " << v.z << " at " << x << " " << y;
  });
}

TEST(DemTerrain, LonLatRasterUnderAUtmCityIsReprojected) {
  const TempDir dir;
  const fs::path tif = dir.path / "lonlat.tif";
  // z linear in lon/lat: bilinear between pixel centres reproduces it exactly, so every TIN node
  // must hold the plane at its own lon/lat, which GeographicLib's UTM gives independently.
  auto plane = [](double lon, double lat) {
    return 100 + 2000 * (lon - 9.0) + 1000 * (lat - 47.0);
  };
  write_geotiff(tif, "EPSG:4326", 8.9, 47.1, 0.001, 0.001, 200, 200, plane);
  int zone = 0;
  bool north = true;
  double x0 = 0, y0 = 0;
  GeographicLib::UTMUPS::Forward(47.0, 9.0, zone, north, x0, y0);
  ASSERT_EQ(zone, 32);
  const LocalFrame frame = projected("EPSG:32632", std::floor(x0), std::floor(y0));
  Box2 area{{-2000, -2000}, {2000, 2000}};
  DemSummary s;
  const Terrain t = read_dem_terrain(tif, frame, area, &s);
  EXPECT_EQ(s.crs, "EPSG:4326");
  EXPECT_EQ(s.filled, 0u);
  EXPECT_NEAR(s.pixel_y, 111.2, 0.5);
  for_each_vertex(t, [&](const Vec3& v) {
    double lat = 0, lon = 0;
    GeographicLib::UTMUPS::Reverse(32, true, v.x + frame.origin[0], v.y + frame.origin[1], lat,
                                   lon);
    ASSERT_NEAR(v.z, plane(lon, lat), 0.01) << "at lon " << lon << " lat " << lat;
  });
}

TEST(DemTerrain, BadRastersNameTheFileAndTheProblem) {
  const TempDir dir;
  const LocalFrame frame = projected("EPSG:28992", 84100, 447100);
  const Box2 area{{0, 0}, {100, 100}};
  auto problem = [&](const fs::path& p) {
    try {
      read_dem_terrain(p, frame, area);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), p.string());
      return std::pair(e.problem(), std::string(e.what()));
    }
    return std::pair(InputProblem::Unreadable, std::string("no error"));
  };
  EXPECT_EQ(problem(dir.path / "none.tif"),
            std::pair(InputProblem::Unreadable,
                      (dir.path / "none.tif").string() + ": unreadable file: no such file"));
  const fs::path text = dir.path / "notes.tif";
  std::ofstream(text) << "not a raster\n";
  const auto [p1, m1] = problem(text);
  EXPECT_EQ(p1, InputProblem::UnsupportedFormat);
  EXPECT_NE(m1.find("notes.tif: unsupported format: not a raster GDAL can read"), std::string::npos)
      << m1;
  // A raster far from the city (the same plane 100 km away).
  const fs::path far = dir.path / "far.tif";
  write_geotiff(far, "EPSG:28992", 184000, 548000, 10, 10, 20, 20,
                [](double, double) { return 1.0; });
  const auto [p2, m2] = problem(far);
  EXPECT_EQ(p2, InputProblem::UnknownCrs);
  EXPECT_NE(m2.find("far.tif: unknown coordinate reference system: the raster (EPSG:28992, 20 x 20 "
                    "pixels) covers none of the city"),
            std::string::npos)
      << m2;
  // A raster of nothing but no-data.
  const fs::path empty = dir.path / "voids.tif";
  write_geotiff(
      empty, "EPSG:28992", 84000, 448000, 10, 10, 100, 100, [](double, double) { return 1.0; },
      [](int, int) { return true; });
  const auto [p3, m3] = problem(empty);
  EXPECT_EQ(p3, InputProblem::UnknownCrs);
  EXPECT_NE(m3.find("holds no height anywhere under the city"), std::string::npos) << m3;
}

// Monaco's OSM buildings stand on the DEM: each one's ground lies within the heights of the
// SRTM posts around its footprint (read from the tile's bytes).
TEST(DemTerrain, MonacoBuildingsStandOnTheSrtmTile) {
  const fs::path pbf = kShared / "monaco-2021.osm.pbf", hgt = kShared / "dem" / "N43E007.hgt";
  if (!fs::exists(pbf) || !fs::exists(hgt)) GTEST_SKIP() << pbf << " or " << hgt << " is absent";
  const SrtmTile tile(hgt, 7, 43);
  ReadOptions options;
  options.terrain_path = hgt;
  const City city = read_city({pbf}, options);
  EXPECT_EQ(city.report.on_terrain, city.objects.size());
  EXPECT_NE(city.report.terrain_note.find("N43E007.hgt (SRTMHGT, EPSG:4326"), std::string::npos)
      << city.report.terrain_note;
  EXPECT_EQ(city.report.osm_multipolygons, 24u);  // SOURCES.md: 24 multipolygons
  const LocalFrameMapping mapping(city.frame);
  std::size_t above_sea = 0;
  for (const CityObject& o : city.objects) {
    Box2 where;
    for (const Polygon& p : o.footprint) where.extend(bounds(p));
    ASSERT_FALSE(where.empty()) << o.source_id;
    const Vec3 a = mapping.to_input(where.min.x, where.min.y, 0);
    const Vec3 b = mapping.to_input(where.max.x, where.max.y, 0);
    // Posts within one post (3") of the footprint's box, plus the TIN's half-post resampling.
    double lo = 1e9, hi = -1e9;
    for (int j = int(std::floor((44 - b.y) * 1200)) - 1; j <= int(std::ceil((44 - a.y) * 1200)) + 1;
         ++j)
      for (int i = int(std::floor((a.x - 7) * 1200)) - 1; i <= int(std::ceil((b.x - 7) * 1200)) + 1;
           ++i)
        lo = std::min(lo, tile.post(i, j)), hi = std::max(hi, tile.post(i, j));
    EXPECT_GE(o.ground_z, lo - 1e-6) << o.source_id;
    EXPECT_LE(o.ground_z, hi + 1e-6) << o.source_id;
    above_sea += o.ground_z > 50;
  }
  EXPECT_GT(above_sea, city.objects.size() / 10);  // the buildings up the slopes are raised
}
