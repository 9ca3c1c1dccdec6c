// SPDX-License-Identifier: GPL-3.0-or-later
// Round trip between two independent implementations: the procedural generator knows each
// building's footprint, eaves and ridge; the CityJSON and GeoJSON readers must recover them from
// the written geometry alone (thesis 7.1: the occluder of a gabled building ends at its eaves).
#include <gtest/gtest.h>

#include <map>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/cities/GeoJsonWriter.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"

namespace urbanpvs::geometry {
namespace {

double generated_area(const cities::Polygon& p) {
  auto ring_area = [](const cities::Ring& r) {
    double a = 0;
    for (std::size_t i = 0; i < r.size(); ++i)
      a += r[i].x * r[(i + 1) % r.size()].y - r[(i + 1) % r.size()].x * r[i].y;
    return 0.5 * std::abs(a);
  };
  double a = ring_area(p.outer);
  for (const auto& h : p.holes) a -= ring_area(h);
  return a;
}

void check_against_generator(const cities::City& gen, const City& city, bool lod2) {
  std::map<std::string, const CityObject*> by_id;
  for (const CityObject& o : city.objects) by_id[o.source_id] = &o;
  ASSERT_EQ(city.objects.size(), gen.buildings.size());
  int gabled = 0;
  for (const cities::Building& b : gen.buildings) {
    ASSERT_TRUE(by_id.count(b.id)) << b.id;
    const CityObject& o = *by_id[b.id];
    double area_read = 0;
    for (const Polygon& p : o.footprint) area_read += area(p);
    EXPECT_NEAR(area_read, generated_area(b.footprint), 1e-3 * (1 + area_read)) << b.id;
    ASSERT_FALSE(o.occluders.empty()) << b.id;
    double lowest_top = 1e300;
    for (const OccluderPrism& p : o.occluders) {
      lowest_top = std::min(lowest_top, p.top_z);
      // Never above the real building: at most its eaves (the lowest roof point of its part).
      EXPECT_LE(p.top_z, b.ground_z + b.eaves_height + 1e-3) << b.id;
    }
    if (b.parts.empty()) {
      EXPECT_NEAR(lowest_top, b.ground_z + b.eaves_height, 1e-3) << b.id;
    }
    EXPECT_NEAR(o.bbox.zmax, b.ground_z + (lod2 ? b.ridge_height : b.eaves_height), 1e-3) << b.id;
    gabled += b.ridge_height > b.eaves_height + 0.5;
  }
  if (lod2) {
    EXPECT_GT(gabled, 50);
  }
}

TEST(GeneratedCity, FlatCityJsonRoundTrip) {
  cities::CityParams params;
  params.size_km2 = 0.25;
  params.seed = 5;
  const cities::City gen = cities::generateCity(params);
  check_against_generator(gen, read_city_text(cities::cityJsonText(gen), "flat.city.json"), false);
}

TEST(GeneratedCity, Lod2CityJsonGivesEavesNotRidge) {
  cities::CityParams params;
  params.size_km2 = 0.25;
  params.seed = 9;
  params.roofs = cities::RoofMode::Lod2;
  const cities::City gen = cities::generateCity(params);
  check_against_generator(gen, read_city_text(cities::cityJsonText(gen), "lod2.city.json"), true);
}

TEST(GeneratedCity, GeoJsonAndCityJsonAgree) {
  cities::CityParams params;
  params.size_km2 = 0.25;
  params.seed = 3;
  const cities::City gen = cities::generateCity(params);
  const City a = read_city_text(cities::cityJsonText(gen), "a.city.json");
  const City b = read_city_text(cities::geoJsonText(gen), "b.geojson");
  EXPECT_EQ(b.frame.crs, "EPSG:31256");
  // GeoJSON has no parent-child link: the generator writes the two parts of a composite
  // building (a tower on a podium) as two building:part features and no outline, so each part
  // becomes an object of its own. Every other building must agree between the two formats.
  std::size_t composites = 0;
  for (const cities::Building& g : gen.buildings) composites += !g.parts.empty();
  ASSERT_EQ(b.objects.size(), a.objects.size() + composites);
  std::map<std::string, const CityObject*> by_id;
  for (const CityObject& o : b.objects) by_id[o.source_id] = &o;
  std::size_t compared = 0;
  for (const CityObject& o : a.objects) {
    if (!by_id.count(o.source_id)) continue;
    ++compared;
    const CityObject& g = *by_id[o.source_id];
    EXPECT_NEAR(o.bbox.xy.min.x, g.bbox.xy.min.x, 1e-6);
    EXPECT_NEAR(o.bbox.xy.max.y, g.bbox.xy.max.y, 1e-6);
    EXPECT_NEAR(o.bbox.zmax, g.bbox.zmax, 1e-3) << o.source_id;
  }
  EXPECT_EQ(compared, a.objects.size() - composites);
}

}  // namespace
}  // namespace urbanpvs::geometry

namespace urbanpvs::geometry {
namespace {

// A TINRelief becomes terrain triangles in the local frame; a Building with a BuildingPart is one
// object whose occluder per part ends at that part's lowest roof point.
TEST(CityJsonInput, TerrainAndParts) {
  const char* text = R"({"type":"CityJSON","version":"2.0",
    "transform":{"scale":[0.01,0.01,0.01],"translate":[1000,2000,0]},
    "metadata":{"referenceSystem":"https://www.opengis.net/def/crs/EPSG/0/7415"},
    "CityObjects":{
      "ground":{"type":"TINRelief","geometry":[{"type":"CompositeSurface","lod":"1",
        "boundaries":[[[0,1,2]],[[0,2,3]]]}]},
      "house":{"type":"Building","children":["wing"],"geometry":[{"type":"Solid","lod":"1.2",
        "boundaries":[[[[4,7,6,5]],[[8,9,10,11]],[[4,5,9,8]],[[5,6,10,9]],[[6,7,11,10]],[[7,4,8,11]]]]}]},
      "wing":{"type":"BuildingPart","parents":["house"],"geometry":[{"type":"Solid","lod":"1.2",
        "boundaries":[[[[12,15,14,13]],[[16,17,18,19]],[[12,13,17,16]],[[13,14,18,17]],[[14,15,19,18]],[[15,12,16,19]]]]}]},
      "tree":{"type":"SolitaryVegetationObject"}},
    "vertices":[[0,0,0],[10000,0,0],[10000,10000,100],[0,10000,100],
      [1000,1000,0],[2000,1000,0],[2000,2000,0],[1000,2000,0],
      [1000,1000,1200],[2000,1000,1200],[2000,2000,1200],[1000,2000,1200],
      [2000,1000,0],[3000,1000,0],[3000,2000,0],[2000,2000,0],
      [2000,1000,600],[3000,1000,600],[3000,2000,600],[2000,2000,600]]})";
  const City city = read_city_text(text, "parts.city.json");
  EXPECT_EQ(city.frame.crs, "EPSG:7415");
  ASSERT_EQ(city.terrain.triangles.size(), 2u);
  EXPECT_DOUBLE_EQ(city.terrain.triangles[0].v[2][2], 1.0);  // z 100 * 0.01
  EXPECT_EQ(city.report.ignored_types.at("SolitaryVegetationObject"), 1u);
  ASSERT_EQ(city.objects.size(), 1u);
  const CityObject& house = city.objects[0];
  EXPECT_EQ(house.source_id, "house");
  ASSERT_EQ(house.occluders.size(), 2u);
  EXPECT_DOUBLE_EQ(house.occluders[0].top_z, 12.0);
  EXPECT_DOUBLE_EQ(house.occluders[1].top_z, 6.0);
  ASSERT_EQ(house.footprint.size(), 1u);  // the two parts share a wall: one footprint
  EXPECT_NEAR(area(house.footprint[0]), 200.0, 1e-9);
  // Local frame: projected input is shifted by the floor of its lower-left corner.
  EXPECT_DOUBLE_EQ(city.frame.origin[0], 1000.0);
  EXPECT_NEAR(house.bbox.xy.min.x, 10.0, 1e-9);
}

}  // namespace
}  // namespace urbanpvs::geometry
