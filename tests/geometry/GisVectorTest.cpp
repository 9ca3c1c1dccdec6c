// SPDX-License-Identifier: GPL-3.0-or-later
// GIS vector input (GisVectorReader.cpp): Shapefile, GeoPackage and FlatGeobuf files, written by
// the test with GDAL's own ogr2ogr (GDALVectorTranslate) from GeoJSON, must read as the GeoJSON
// they were made from: Helsinki's footprints to the last bit where the coordinates are kept, a
// district reprojected to metres or to feet within what the projections distort. Layers, the
// height field and bad files give the exact errors.
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "SameCity.hpp"
#include "SharedCities.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace fs = std::filesystem;
using namespace urbanpvs::geometry;

namespace {

const fs::path kScratch =
    fs::temp_directory_path() / ("urbanpvs_gis_" + std::to_string(::getpid()));

// The files the tests write, removed when they are done.
struct ScratchFolder : ::testing::Environment {
  void TearDown() override { fs::remove_all(kScratch); }
};
[[maybe_unused]] const ::testing::Environment* const kScratchFolder =
    ::testing::AddGlobalTestEnvironment(new ScratchFolder);

fs::path scratch(const std::string& name) {
  fs::create_directories(kScratch);
  return kScratch / name;
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

// ogr2ogr `args` `dst` `src`, through the library (gdal-bin is not a dependency).
void translate(const fs::path& src, const fs::path& dst, std::vector<std::string> args) {
  GDALAllRegister();
  GDALDatasetH in = GDALOpenEx(src.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  ASSERT_NE(in, nullptr) << src;
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  GDALVectorTranslateOptions* o = GDALVectorTranslateOptionsNew(argv.data(), nullptr);
  ASSERT_NE(o, nullptr);
  int usage_error = 0;
  const bool update = std::find(args.begin(), args.end(), "-update") != args.end();
  GDALDatasetH out = GDALVectorTranslate(
      update ? nullptr : dst.c_str(),
      update ? GDALOpenEx(dst.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, nullptr, nullptr, nullptr)
             : nullptr,
      1, &in, o, &usage_error);
  GDALVectorTranslateOptionsFree(o);
  ASSERT_NE(out, nullptr) << dst << ": " << CPLGetLastErrorMsg();
  GDALClose(out);
  GDALClose(in);
}

// A district near Manhattan in lon/lat: a 20 x 30 m block of 15 m (16 m by the dataset's own
// field), a courtyard block of 24 m with a 10 x 10 m yard, and a footprint whose height is only
// in the dataset's own field.
std::string district_geojson() {
  const double lon0 = -73.99, lat0 = 40.75;
  const double mx = 1 / (111320.0 * std::cos(lat0 * M_PI / 180)), my = 1 / 110574.0;
  auto ring = [&](double x0, double y0, double w, double h) {
    char b[400];
    std::snprintf(b, sizeof b, "[[%.9f,%.9f],[%.9f,%.9f],[%.9f,%.9f],[%.9f,%.9f],[%.9f,%.9f]]",
                  lon0 + x0 * mx, lat0 + y0 * my, lon0 + (x0 + w) * mx, lat0 + y0 * my,
                  lon0 + (x0 + w) * mx, lat0 + (y0 + h) * my, lon0 + x0 * mx, lat0 + (y0 + h) * my,
                  lon0 + x0 * mx, lat0 + y0 * my);
    return std::string(b);
  };
  auto hole = [&](double x0, double y0, double w, double h) {  // clockwise
    char b[400];
    std::snprintf(b, sizeof b, "[[%.9f,%.9f],[%.9f,%.9f],[%.9f,%.9f],[%.9f,%.9f],[%.9f,%.9f]]",
                  lon0 + x0 * mx, lat0 + y0 * my, lon0 + x0 * mx, lat0 + (y0 + h) * my,
                  lon0 + (x0 + w) * mx, lat0 + (y0 + h) * my, lon0 + (x0 + w) * mx, lat0 + y0 * my,
                  lon0 + x0 * mx, lat0 + y0 * my);
    return std::string(b);
  };
  return R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{"id":"a","height":15.0,"HOEHE":16.0},"geometry":{"type":"Polygon","coordinates":[)" +
         ring(0, 0, 20, 30) + R"(]}},
{"type":"Feature","properties":{"id":"b","height":24.0},"geometry":{"type":"Polygon","coordinates":[)" +
         ring(40, 0, 30, 30) + "," + hole(50, 10, 10, 10) + R"(]}},
{"type":"Feature","properties":{"id":"c","HOEHE":"9.5"},"geometry":{"type":"Polygon","coordinates":[)" +
         ring(0, 50, 20, 20) + R"(]}}]})";
}

double footprint_area(const CityObject& o) {
  double a = 0;
  for (const Polygon& p : o.footprint) {
    auto ring_area = [](const Ring& r) {
      double s = 0;
      for (std::size_t i = 0; i < r.size(); ++i)
        s += r[i].x * r[(i + 1) % r.size()].y - r[(i + 1) % r.size()].x * r[i].y;
      return std::abs(s) / 2;
    };
    a += ring_area(p.outer);
    for (const Ring& h : p.holes) a -= ring_area(h);
  }
  return a;
}

std::map<std::string, const CityObject*> by_id(const City& c) {
  std::map<std::string, const CityObject*> m;
  for (const CityObject& o : c.objects) m[o.source_id] = &o;
  return m;
}

// The problem and message read_city throws for `path`.
std::pair<InputProblem, std::string> error_of(const fs::path& path, const ReadOptions& o = {}) {
  try {
    (void)read_city({path.string()}, o);
  } catch (const InputError& e) {
    return {e.problem(), e.what()};
  }
  return {InputProblem::Unreadable, "(no error)"};
}

TEST(GisVector, HelsinkiAsGeoPackageAndFlatGeobufReadsAsItsGeoJson) {
  REQUIRE_SHARED_CITY(geojson, "helsinki_buildings.geojson");
  ReadOptions options;
  options.default_height = 10;
  const City expected = read_city({geojson}, options);
  for (const char* ext : {".gpkg", ".fgb"}) {
    const fs::path out = scratch(std::string("helsinki") + ext);
    fs::remove(out);
    // FlatGeobuf sorts features along a Hilbert curve for its index; without the index it
    // keeps the file's order, in which building parts join their buildings.
    translate(geojson, out,
              ext == std::string(".fgb") ? std::vector<std::string>{"-lco", "SPATIAL_INDEX=NO"}
                                         : std::vector<std::string>{});
    const City got = read_city({out.string()}, options);
    SCOPED_TRACE(ext);
    EXPECT_EQ(got.frame.kind, expected.frame.kind);
    urbanpvs::test::expect_same_city(expected, got);
  }
}

TEST(GisVector, ProjectedMetresKeepTheirSystemAndFeetAreTransformed) {
  const fs::path src = scratch("district.geojson");
  write(src, district_geojson());
  ReadOptions options;
  options.height_field = "HOEHE";
  const City lonlat = read_city({src.string()}, options);
  ASSERT_EQ(lonlat.objects.size(), 3u);
  // UTM 18N in metres: kept, the frame names it. NY Long Island in US survey feet: back to
  // WGS84 lon/lat, said in a warning. A zipped shapefile is read in place.
  struct Case {
    const char* file;
    const char* srs;
    LocalFrame::Kind kind;
    const char* crs;
  };
  for (const Case& c :
       {Case{"utm.gpkg", "EPSG:32618", LocalFrame::Kind::Projected, "EPSG:32618"},
        Case{"feet.shp", "EPSG:2263", LocalFrame::Kind::Geographic, "OGC:CRS84"},
        Case{"feet.shp.zip", "EPSG:2263", LocalFrame::Kind::Geographic, "OGC:CRS84"},
        // Web Mercator's metres are 1.32 true metres here: transformed too.
        Case{"web.fgb", "EPSG:3857", LocalFrame::Kind::Geographic, "OGC:CRS84"}}) {
    SCOPED_TRACE(c.file);
    const fs::path out = scratch(c.file);
    fs::remove(out);
    translate(src, out, {"-t_srs", c.srs});
    const City got = read_city({out.string()}, options);
    EXPECT_EQ(got.frame.kind, c.kind);
    EXPECT_EQ(got.frame.crs, c.crs);
    const bool transformed = c.kind == LocalFrame::Kind::Geographic;
    bool said = false;
    for (const std::string& w : got.report.warnings)
      said |= w.find("transformed to WGS84 lon/lat") != std::string::npos;
    EXPECT_EQ(said, transformed);
    const auto want = by_id(lonlat), have = by_id(got);
    ASSERT_EQ(have.size(), 3u);
    for (const auto& [id, o] : want) {
      ASSERT_TRUE(have.count(id)) << id;
      const CityObject& g = *have.at(id);
      EXPECT_EQ(g.occludes, o->occludes) << id;
      EXPECT_DOUBLE_EQ(g.bbox.zmax, o->bbox.zmax) << id;
      // UTM's scale near its central meridian's 3° east: within 0.1 % in area; the round trip
      // through feet: the same to a millimetre's worth.
      EXPECT_NEAR(footprint_area(g), footprint_area(*o),
                  (transformed ? 1e-5 : 1e-3) * footprint_area(*o))
          << id;
    }
    EXPECT_NEAR(footprint_area(*have.at("b")), 30 * 30 - 10 * 10, 10) << "the yard is a hole";
    EXPECT_DOUBLE_EQ(have.at("c")->bbox.zmax, 9.5) << "height from --height-field";
  }
}

TEST(GisVector, HeightFieldComesFirstAndIsNamedWhenMissing) {
  const fs::path src = scratch("district_fields.geojson");
  write(src, district_geojson());
  const City without = read_city({src.string()});
  EXPECT_FALSE(by_id(without).at("c")->occludes) << "no height known";
  EXPECT_DOUBLE_EQ(by_id(without).at("a")->bbox.zmax, 15);
  ReadOptions options;
  options.height_field = "HOEHE";
  const City with = read_city({src.string()}, options);
  EXPECT_TRUE(by_id(with).at("c")->occludes);
  EXPECT_DOUBLE_EQ(by_id(with).at("a")->bbox.zmax, 16) << "the named field before height";
  options.height_field = "HOHE";
  bool warned = false;
  for (const std::string& w : read_city({src.string()}, options).report.warnings)
    warned |=
        w == src.string() + ": --height-field HOHE: no feature has this property, field or tag";
  EXPECT_TRUE(warned) << "a misspelt field name";
  options.height_field = "h_max";
  options.strict = true;
  const auto [problem, what] = error_of(src, options);
  EXPECT_EQ(problem, InputProblem::MissingHeight);
  EXPECT_EQ(what, src.string() +
                      ": c: missing height: no h_max, height, building:height, measuredHeight, "
                      "building:levels or num_floors "
                      "(give a default height; --strict refuses objects of unknown height)");
}

// Ids: a feature's own "id" (or "@id") field, matched exactly, else its FID: ArcGIS's "ID"
// field of zeros is none. Walls standing on edge (3D surfaces) are left out, the footprint beside
// them kept.
TEST(GisVector, IdsAreFidsUnlessTheFeatureNamesItselfAndWallsAreLeftOut) {
  const fs::path src = scratch("ids.geojson");
  write(src, R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{"ID":0,"height":10},"geometry":{"type":"MultiPolygon","coordinates":[
 [[[24.9500,60.1700,0],[24.9502,60.1700,0],[24.9502,60.1701,0],[24.9500,60.1701,0],[24.9500,60.1700,0]]],
 [[[24.9500,60.1700,0],[24.9502,60.1700,0],[24.9502,60.1700,10],[24.9500,60.1700,10],[24.9500,60.1700,0]]]]}},
{"type":"Feature","properties":{"ID":0,"@id":"own","height":10},"geometry":{"type":"Polygon","coordinates":[
 [[24.9505,60.1700,0],[24.9507,60.1700,0],[24.9507,60.1701,0],[24.9505,60.1701,0],[24.9505,60.1700,0]]]}}]})");
  const fs::path out = scratch("ids.gpkg");
  fs::remove(out);
  translate(src, out, {});
  const City city = read_city({out.string()});
  const auto ids = by_id(city);
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_TRUE(ids.count("1")) << "the first feature's FID";
  EXPECT_TRUE(ids.count("own"));
  EXPECT_NEAR(footprint_area(*ids.at("1")), footprint_area(*ids.at("own")), 1e-6);
  bool warned = false;
  for (const std::string& w : city.report.warnings)
    warned |= w.find("1 vertical polygon(s)") != std::string::npos;
  EXPECT_TRUE(warned);
}

// A damaged file ends in an error, not in a smaller city.
TEST(GisVector, ATruncatedShapefileIsAnError) {
  const fs::path dir = scratch("truncated");
  fs::create_directories(dir);
  for (const char* ext : {".shp", ".shx", ".dbf", ".prj"})
    fs::copy_file(fs::path(URBANPVS_TEST_DATA) / "gis" / (std::string("district") + ext),
                  dir / (std::string("district") + ext), fs::copy_options::overwrite_existing);
  fs::resize_file(dir / "district.shp", 600);
  const auto [problem, what] = error_of(dir / "district.shp");
  EXPECT_EQ(problem, InputProblem::Unreadable);
  EXPECT_EQ(what.rfind((dir / "district.shp").string() +
                           ": district: unreadable file: reading stopped after",
                       0),
            0u)
      << what;
}

TEST(GisVector, SeveralLayersOfPolygonsNeedALayerName) {
  const fs::path src = scratch("layers.geojson");
  write(src, district_geojson());
  const fs::path out = scratch("layers.gpkg");
  fs::remove(out);
  translate(src, out, {"-nln", "lod12"});
  translate(src, out, {"-update", "-nln", "lod22"});
  const auto [problem, what] = error_of(out);
  EXPECT_EQ(problem, InputProblem::BadStructure);
  EXPECT_EQ(what,
            out.string() +
                ": unexpected structure: 2 layers of polygons (lod12, lod22): name the one to read "
                "with --layer");
  ReadOptions options;
  options.layer = "lod22";
  EXPECT_EQ(read_city({out.string()}, options).objects.size(), 3u);
  options.layer = "lod13";
  const auto [no_layer, no_layer_what] = error_of(out, options);
  EXPECT_EQ(no_layer, InputProblem::BadStructure);
  EXPECT_EQ(no_layer_what,
            out.string() + ": unexpected structure: no layer \"lod13\" (layers: lod12, lod22)");
}

TEST(GisVector, PointsAreNoBuildingsAndOtherBytesAreNoGisFile) {
  const fs::path points = scratch("points.geojson");
  write(points, R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},
    "geometry":{"type":"Point","coordinates":[24.95,60.17]}}]})");
  const fs::path gpkg = scratch("points.gpkg");
  fs::remove(gpkg);
  translate(points, gpkg, {"-nln", "trees"});
  const auto [empty, empty_what] = error_of(gpkg);
  EXPECT_EQ(empty, InputProblem::EmptyCity);
  EXPECT_EQ(empty_what, gpkg.string() + ": empty city: no layer of polygons (layers: trees)");

  const fs::path text = scratch("notes.gpkg");
  write(text, "not a GeoPackage\n");
  const auto [unsupported, unsupported_what] = error_of(text);
  EXPECT_EQ(unsupported, InputProblem::UnsupportedFormat);
  EXPECT_EQ(unsupported_what.rfind(
                text.string() +
                    ": unsupported format: no vector data GDAL can read (Shapefile, GeoPackage, "
                    "FlatGeobuf, ...)",
                0),
            0u)
      << unsupported_what;

  const auto [missing, missing_what] = error_of(scratch("absent.shp"));
  EXPECT_EQ(missing, InputProblem::Unreadable);
  EXPECT_EQ(missing_what, scratch("absent.shp").string() + ": unreadable file: no such file");
}

}  // namespace
