// SPDX-License-Identifier: GPL-3.0-or-later
// Input whose coordinates are not metres as they stand (feet, Mercator, degrees on another datum
// than WGS84) reads in metres: each expected size is worked out here from the system's own
// definition, not by the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>

#include "TextFile.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace {

using namespace urbanpvs::geometry;

const std::string kTestData = URBANPVS_TEST_DATA;

// A FeatureCollection of one square building, 15 m tall, in `crs`.
std::string square_geojson(const std::string& crs, double x, double y, double side) {
  auto pos = [](double a, double b) {
    char s[96];
    std::snprintf(s, sizeof s, "[%.10f, %.10f]", a, b);
    return std::string(s);
  };
  return R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": ")" + crs +
         R"("}}, "features": [{"type": "Feature", "id": "a", "properties": {"height": 15},
         "geometry": {"type": "Polygon", "coordinates": [[)" +
         pos(x, y) + ", " + pos(x + side, y) + ", " + pos(x + side, y + side) + ", " +
         pos(x, y + side) + ", " + pos(x, y) + "]]}}]}";
}

double footprint_area(const City& city) {
  EXPECT_EQ(city.objects.size(), 1u);
  EXPECT_EQ(city.objects.at(0).occluders.size(), 1u);
  return area(city.objects.at(0).occluders.at(0).footprint);
}

void expect_transformed(const City& city, const std::string& from) {
  EXPECT_EQ(city.frame.kind, LocalFrame::Kind::Geographic);
  EXPECT_EQ(city.frame.crs, "OGC:CRS84");
  EXPECT_NE(city.report.coordinate_note.find(from + " transformed to WGS84 lon/lat"),
            std::string::npos)
      << city.report.coordinate_note;
}

TEST(InputReprojection, StatePlaneInFeetReadsInMetres) {
  // 100 US survey feet (1200/3937 m each) in Manhattan; the state plane's scale there is within
  // 1e-4 of 1, so the area is within 0.02 % of (30.48 m)².
  const City city =
      read_city_text(square_geojson("urn:ogc:def:crs:EPSG::2263", 987000, 211000, 100), "ft.json");
  expect_transformed(city, "EPSG:2263 (in US survey foot)");
  const double side = 100 * 1200.0 / 3937.0;
  EXPECT_NEAR(footprint_area(city), side * side, 2e-4 * side * side);
  EXPECT_NEAR(city.frame.origin_lat, 40.75, 0.05);  // midtown, not 3.28 times as far out
  EXPECT_NEAR(city.frame.origin_lon, -73.98, 0.05);
  const Box3 b = city.objects[0].bbox;
  EXPECT_DOUBLE_EQ(b.zmax - b.zmin, 15.0);  // a GeoJSON height is a property, in metres
}

// A GeometryCollection's polygon is transformed as a Polygon is: the same square in the same
// place.
TEST(InputReprojection, GeometryCollectionMembersAreTransformedToo) {
  const std::string plain = square_geojson("urn:ogc:def:crs:EPSG::2263", 987000, 211000, 100);
  std::string collection = plain;
  const std::string polygon = R"("geometry": {"type": "Polygon",)";
  const auto at = collection.find(polygon);
  ASSERT_NE(at, std::string::npos);
  collection.replace(at, polygon.size(),
                     R"("geometry": {"type": "GeometryCollection", "geometries": [{"type": )"
                     R"("Polygon",)");
  ASSERT_EQ(collection.substr(collection.size() - 6), "]]}}]}");
  collection.replace(collection.size() - 6, 6, "]]}]}}]}");
  const City a = read_city_text(plain, "ft.json");
  const City b = read_city_text(collection, "ft.json");
  expect_transformed(b, "EPSG:2263 (in US survey foot)");
  EXPECT_NEAR(footprint_area(b), footprint_area(a), 1e-9 * footprint_area(a));
  EXPECT_DOUBLE_EQ(b.frame.origin_lat, a.frame.origin_lat);
  EXPECT_DOUBLE_EQ(b.frame.origin_lon, a.frame.origin_lon);
}

TEST(InputReprojection, WebMercatorReadsInTrueMetres) {
  // Web Mercator is the spherical formula on WGS84 lon/lat: northing y lies at latitude
  // 2·atan(exp(y/a)) − π/2, where one of its "metres" is cos(latitude) true metres (to the
  // ellipsoid's 0.3 %). The same square named by Esri's code for the system reads the same.
  const double a = 6378137, y = 8437000, side = 20;
  const double lat = 2 * std::atan(std::exp((y + side / 2) / a)) - std::numbers::pi / 2;
  const double true_side = side * std::cos(lat);
  const City epsg =
      read_city_text(square_geojson("urn:ogc:def:crs:EPSG::3857", 2777000, y, side), "m.json");
  expect_transformed(epsg, "EPSG:3857 (Mercator)");
  EXPECT_NEAR(footprint_area(epsg), true_side * true_side, 0.01 * true_side * true_side);
  const City esri =
      read_city_text(square_geojson("urn:ogc:def:crs:ESRI::102100", 2777000, y, side), "e.json");
  EXPECT_NEAR(footprint_area(esri), footprint_area(epsg), 1e-9 * footprint_area(epsg));
}

TEST(InputReprojection, DegreesOnAnotherDatumReadAsLongitudeAndLatitude) {
  // ETRS89 and WGS84 agree to a metre, which moves the city as a whole: the same square in
  // EPSG:4258 and in WGS84 has the same shape.
  const City etrs = read_city_text(square_geojson("urn:ogc:def:crs:EPSG::4258", 7.44, 46.95, 1e-4),
                                   "etrs89.json");
  expect_transformed(etrs, "EPSG:4258 (degrees)");
  const City wgs = read_city_text(
      square_geojson("urn:ogc:def:crs:OGC:1.3:CRS84", 7.44, 46.95, 1e-4), "wgs84.json");
  EXPECT_NEAR(footprint_area(etrs), footprint_area(wgs), 1e-3);
  EXPECT_NEAR(etrs.frame.origin_lat, wgs.frame.origin_lat, 1e-4);
}

TEST(InputReprojection, CityJsonInFeetHasItsHeightsInFeetToo) {
  // A box of 100 x 100 x 50 US survey feet, vertices in hundredths of a foot.
  const std::string text = R"({"type": "CityJSON", "version": "2.0",
    "transform": {"scale": [0.01, 0.01, 0.01], "translate": [987000, 211000, 0]},
    "metadata": {"referenceSystem": "https://www.opengis.net/def/crs/EPSG/0/2263"},
    "CityObjects": {"box": {"type": "Building", "geometry": [{"type": "Solid", "lod": "1",
      "boundaries": [[[[0, 3, 2, 1]], [[4, 5, 6, 7]], [[0, 1, 5, 4]], [[1, 2, 6, 5]],
                      [[2, 3, 7, 6]], [[3, 0, 4, 7]]]]}]}},
    "vertices": [[0, 0, 0], [10000, 0, 0], [10000, 10000, 0], [0, 10000, 0],
                 [0, 0, 5000], [10000, 0, 5000], [10000, 10000, 5000], [0, 10000, 5000]]})";
  const City city = read_city_text(text, "box.city.json");
  expect_transformed(city, "EPSG:2263 (in US survey foot)");
  const double foot = 1200.0 / 3937.0, side = 100 * foot;
  EXPECT_NEAR(footprint_area(city), side * side, 2e-4 * side * side);
  const OccluderPrism& p = city.objects[0].occluders[0];
  EXPECT_NEAR(p.top_z - p.ground_z, 50 * foot, 1e-9);
}

TEST(InputReprojection, CityGmlInJgd2011TakesLatitudeFirst) {
  // Japan's PLATEAU models are CityGML in EPSG:6697 (JGD2011 latitude, longitude, height): the
  // EPSG:4979 file's building of 10 x 10 m, named in JGD2011 instead.
  std::string text = urbanpvs::test::read_text(kTestData + "/citygml/latitude_first_epsg4979.gml");
  const std::string from = "EPSG/0/4979";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "EPSG/0/6697");
  const City city = read_city_text(text, "plateau.gml");
  expect_transformed(city, "EPSG:6697 (degrees)");
  const Box3 b = city.objects.at(0).bbox;
  // Swapped axes would give 13.7 x 7.3 m.
  EXPECT_NEAR(b.xy.max.x - b.xy.min.x, 10.0, 0.05);
  EXPECT_NEAR(b.xy.max.y - b.xy.min.y, 10.0, 0.05);
  EXPECT_NEAR(city.frame.origin_lat, 47.0, 1e-3);
  EXPECT_NEAR(city.objects[0].occluders.at(0).top_z - city.objects[0].occluders[0].ground_z, 15.0,
              1e-6);
}

TEST(InputReprojection, SwissDatumNamesAreTheirGridsAndUnknownNamesStayErrors) {
  // Swiss 3D City Database exports name the datum alone: "CH1903" for the LV03 grid and
  // "CH1903+" for LV95, both in metres (PROJ alone would take the geographic systems of those
  // names). Nothing is transformed.
  const std::string box = R"({"type": "CityJSON", "version": "2.0",
    "transform": {"scale": [0.001, 0.001, 0.001], "translate": [683000, 247000, 400]},
    "metadata": {"referenceSystem": "NAME"},
    "CityObjects": {"house": {"type": "Building", "geometry": [{"type": "MultiSurface",
      "lod": "1", "boundaries": [[[0, 3, 2, 1]], [[4, 5, 6, 7]], [[0, 1, 5, 4]], [[1, 2, 6, 5]],
                                 [[2, 3, 7, 6]], [[3, 0, 4, 7]]]}]}},
    "vertices": [[0, 0, 0], [10000, 0, 0], [10000, 10000, 0], [0, 10000, 0],
                 [0, 0, 12000], [10000, 0, 12000], [10000, 10000, 12000], [0, 10000, 12000]]})";
  for (const auto& [name, code] :
       {std::pair<std::string, std::string>{"CH1903", "EPSG:21781"}, {"CH1903+", "EPSG:2056"}}) {
    std::string text = box;
    text.replace(text.find("NAME"), 4, name);
    const City city = read_city_text(text, "named.city.json");
    EXPECT_EQ(city.frame.kind, LocalFrame::Kind::Projected) << name;
    EXPECT_EQ(city.frame.crs, code) << name;
    EXPECT_DOUBLE_EQ(footprint_area(city), 100.0) << name;
  }
  // A name nobody knows stays an error (exit 13), not a guess.
  std::string text = box;
  text.replace(text.find("NAME"), 4, "urn:example:crs:LocalGrid");
  try {
    (void)read_city_text(text, "unknown.city.json");
    ADD_FAILURE() << "an unknown reference system was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::UnknownCrs);
  }
}

}  // namespace
