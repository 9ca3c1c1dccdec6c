// SPDX-License-Identifier: GPL-3.0-or-later
// Occluders never larger than the real building (thesis 7.1: an occluder must be a subset of the
// building, else the PVS misses what it seems to hide). Each test reads a small hand-written
// file of tests/data/occluders and checks the exact occluder top, footprint, raised-ness, box or
// refusal; every one of them failed with the readers as they were before these rules.
// The files lie in EPSG:28992 (metres) around (85000, 446000); heights are metres, and the local
// frame keeps z as it is, so heights are compared directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"

namespace urbanpvs::geometry {
namespace {

namespace fs = std::filesystem;

std::string data(const char* name) {
  return (fs::path(URBANPVS_TEST_DATA) / "occluders" / name).string();
}

const CityObject& object(const City& c, const std::string& id) {
  for (const CityObject& o : c.objects)
    if (o.source_id == id) return o;
  throw std::runtime_error("no object " + id);
}

// The single occluder's top of `id` (fails the test unless it has exactly one).
double occluder_top(const City& c, const std::string& id) {
  const CityObject& o = object(c, id);
  if (o.occluders.size() != 1) {
    ADD_FAILURE() << id << " has " << o.occluders.size() << " occluders, not 1";
    return NAN;
  }
  return o.occluders[0].top_z;
}

double occluder_area(const CityObject& o) {
  double a = 0;
  for (const OccluderPrism& p : o.occluders) a += area(p.footprint);
  return a;
}

// The bounds of every occluder footprint of `o` in input coordinates (EPSG:28992) minus
// (85000, 446000), where the files place their buildings.
Box2 occluder_bounds(const City& c, const CityObject& o) {
  const LocalFrameMapping m(c.frame);
  Box2 b;
  for (const OccluderPrism& p : o.occluders)
    for (Vec2 q : p.footprint.outer) {
      const auto in = m.to_input(q.x, q.y, 0);
      b.extend(Vec2{in[0] - 85000, in[1] - 446000});
    }
  return b;
}

std::pair<double, double> surface_z_range(const CityObject& o) {
  double lo = INFINITY, hi = -INFINITY;
  for (const Surface3& s : o.surfaces)
    for (const auto& r : s.rings)
      for (const auto& v : r) lo = std::min(lo, v[2]), hi = std::max(hi, v[2]);
  return {lo, hi};
}

// ---- 1. GeoJSON: `height` is the roof's top; a pitched roof's occluder ends at the eaves ----

TEST(GeoJsonRoof, PitchedRoofOccluderEndsAtTheEaves) {
  const City c = read_city({data("geojson_roofs.geojson")});
  EXPECT_DOUBLE_EQ(occluder_top(c, "gabled-roof-height"), 8.0);   // 12 - roof:height 4
  EXPECT_DOUBLE_EQ(occluder_top(c, "hipped-roof-levels"), 9.0);   // 12 - 1 roof level x 3
  EXPECT_DOUBLE_EQ(occluder_top(c, "gabled-levels"), 9.0);        // 3 storeys x 3 below 12
  EXPECT_NEAR(occluder_top(c, "gabled-feet"), 12 - 3.048, 1e-9);  // "Gabled", "10 ft"
  // roof:height without roof:shape is a roof all the same (more conservative than flat).
  EXPECT_DOUBLE_EQ(occluder_top(c, "no-shape-roof-height"), 10.0);
  // A flat roof keeps the full height.
  EXPECT_DOUBLE_EQ(occluder_top(c, "flat-roof-height"), 12.0);
  // The box still reaches the ridge: it says where the building may be seen.
  for (const char* id : {"gabled-roof-height", "hipped-roof-levels", "gabled-levels", "gabled-feet",
                         "no-shape-roof-height", "flat-roof-height"})
    EXPECT_DOUBLE_EQ(object(c, id).bbox.zmax, 12.0) << id;
  // Cut: the six above but flat, and the two of unknown eaves (next test).
  EXPECT_EQ(c.report.roof_eaves, 7u);
}

TEST(GeoJsonRoof, PitchedRoofWithoutEavesGivesNoOccluderVolume) {
  const City c = read_city({data("geojson_roofs.geojson")});
  // Neither roof:height, roof:levels nor building:levels below the height: where the walls end
  // is unknown, so the eaves are taken at min_height (0) and nothing is extruded.
  for (const char* id : {"dome-nothing", "gabled-levels-too-high"}) {
    const CityObject& o = object(c, id);
    EXPECT_TRUE(o.occluders.empty()) << id;
    EXPECT_TRUE(o.occludes) << id;  // its surfaces are real: the validator keeps them
    EXPECT_DOUBLE_EQ(o.bbox.zmax, 12.0) << id;
    EXPECT_DOUBLE_EQ(surface_z_range(o).second, 12.0) << id;
  }
}

TEST(GeoJsonRoof, StoreysLieBelowTheRoof) {
  const City c = read_city({data("geojson_roofs.geojson")});
  // building:levels 4 (OSM: without roof levels) + roof:levels 1: walls 12 m, roof top 15 m.
  EXPECT_DOUBLE_EQ(occluder_top(c, "levels-with-roof"), 12.0);
  EXPECT_DOUBLE_EQ(object(c, "levels-with-roof").bbox.zmax, 15.0);
}

// Overture Maps' buildings theme names storeys, roof and base its own way (num_floors,
// roof_shape, roof_height, min_floor) and writes null for what it does not know; it and OSM
// mark buildings below the street (is_underground, location=underground).
TEST(GeoJsonOverture, ItsKeysGiveStoreysRoofsBasesAndWhatLiesUnderground) {
  auto square = [](const char* id, double x, const char* props) {
    char f[600];
    std::snprintf(f, sizeof f,
                  R"({"type":"Feature","id":"%s","properties":%s,"geometry":{"type":"Polygon",)"
                  R"("coordinates":[[[%.1f,446000],[%.1f,446000],[%.1f,446010],[%.1f,446010],)"
                  R"([%.1f,446000]]]}})",
                  id, props, 85000 + x, 85010 + x, 85010 + x, 85000 + x, 85000 + x);
    return std::string(f);
  };
  const std::string text =
      R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"EPSG:28992"}},)"
      R"("features":[)" +
      square("floors", 0, R"({"height":null,"num_floors":4,"roof_shape":null})") + "," +
      square("gabled", 20, R"({"height":12,"roof_shape":"gabled","roof_height":4})") + "," +
      square("raised", 40, R"({"height":10,"min_floor":2})") + "," +
      square("unknown", 60, R"({"height":null,"num_floors":null})") + "," +
      square("garage", 80, R"({"height":6,"is_underground":true})") + "," +
      square("osm-garage", 100, R"({"building":"yes","location":"underground","height":6})") + "]}";
  const City c = read_city_text(text, "overture.geojson", {});
  EXPECT_DOUBLE_EQ(occluder_top(c, "floors"), 12.0);  // 4 storeys x 3 m
  EXPECT_DOUBLE_EQ(object(c, "floors").bbox.zmax, 12.0);
  EXPECT_DOUBLE_EQ(occluder_top(c, "gabled"), 8.0);  // the eaves: 12 - roof_height 4
  EXPECT_DOUBLE_EQ(object(c, "gabled").bbox.zmax, 12.0);
  EXPECT_DOUBLE_EQ(object(c, "raised").bbox.zmin, 6.0);  // 2 floors x 3 m above the ground
  for (const OccluderPrism& p : object(c, "raised").occluders) EXPECT_GE(p.ground_z, 6.0);
  EXPECT_FALSE(object(c, "unknown").occludes);
  EXPECT_TRUE(object(c, "unknown").occluders.empty());
  // Below the street: neither an occluder nor a surface that blocks the validator's rays.
  for (const char* id : {"garage", "osm-garage"}) {
    EXPECT_FALSE(object(c, id).occludes) << id;
    EXPECT_TRUE(object(c, id).occluders.empty()) << id;
    EXPECT_TRUE(object(c, id).surfaces.empty()) << id;
  }
}

// ---- 2. GeoJSON: no occluder volume below min_height / building:min_level ----

TEST(GeoJsonMinHeight, NoOccluderVolumeBelowTheBase) {
  const City c = read_city({data("geojson_min_height.geojson")});
  const CityObject& hall = object(c, "hall");
  // Only the part on the ground: hall-low, 0..10 x 0..10 up to 6 m. hall-bridge starts at 4 m;
  // hall-unreadable's min_height cannot be read, so where it starts is unknown.
  ASSERT_EQ(hall.occluders.size(), 1u);
  EXPECT_DOUBLE_EQ(hall.occluders[0].ground_z, 0.0);
  EXPECT_DOUBLE_EQ(hall.occluders[0].top_z, 6.0);
  EXPECT_NEAR(area(hall.occluders[0].footprint), 100.0, 1e-6);
  EXPECT_NEAR(occluder_bounds(c, hall).max.x, 10.0, 1e-6);
  EXPECT_DOUBLE_EQ(hall.bbox.zmax, 15.0);
  const auto& w = c.report.warnings;
  EXPECT_TRUE(std::any_of(w.begin(), w.end(), [](const std::string& s) {
    return s.find("hall-unreadable") != std::string::npos &&
           s.find("no occluder") != std::string::npos;
  }));
  // building:min_level 2 x 3 m: the building starts at 6 m.
  const CityObject& stilts = object(c, "stilts");
  EXPECT_TRUE(stilts.occluders.empty());
  EXPECT_DOUBLE_EQ(stilts.bbox.zmin, 6.0);
  EXPECT_DOUBLE_EQ(stilts.bbox.zmax, 12.0);
  EXPECT_DOUBLE_EQ(surface_z_range(stilts).first, 6.0);
}

// ---- 3. GeoJSON buildings stand on the terrain of a CityJSON file read with them ----

// terrain.city.json: a TIN shaped like an inverted pyramid over 0..100 x 0..100, 2 m at its
// centre (50, 50) and 10 m at its corners: z = 2 + 8 max(|x - 50|, |y - 50|) / 50.
void expect_on_terrain(const City& c) {
  struct Expected {
    const char* id;
    double lo, hi;  // lowest and highest terrain under the footprint
    double eaves, height;
  };
  for (const Expected& e :
       {Expected{"on-dip", 2.0, 3.6, 10, 10},          // lowest: the TIN vertex inside
        Expected{"on-slope", 5.2, 8.4, 7, 10},         // corners; gabled, roof:height 3
        Expected{"across-ridges", 3.6, 6.8, 10, 10}})  // lowest where TIN edges cross
  {
    const CityObject& o = object(c, e.id);
    ASSERT_EQ(o.occluders.size(), 1u) << e.id;
    EXPECT_NEAR(o.ground_z, e.lo, 1e-9) << e.id;
    EXPECT_NEAR(o.occluders[0].ground_z, e.lo, 1e-9) << e.id;
    EXPECT_NEAR(o.occluders[0].top_z, e.lo + e.eaves, 1e-9) << e.id;
    EXPECT_NEAR(o.bbox.zmin, e.lo, 1e-9) << e.id;
    EXPECT_NEAR(o.bbox.zmax, e.hi + e.height, 1e-9) << e.id;
    const auto [slo, shi] = surface_z_range(o);
    EXPECT_NEAR(slo, e.lo, 1e-9) << e.id;
    EXPECT_NEAR(shi, e.lo + e.height, 1e-9) << e.id;
    // The gabled roof's prisms (RoofShapes.hpp) stand where its occluder stands, under the
    // ridge (lowest ground + height) and above the eaves somewhere.
    const bool gabled = std::string(e.id) == "on-slope";
    EXPECT_EQ(o.roof_prisms.empty(), !gabled) << e.id;
    for (const RoofPrism& p : o.roof_prisms) {
      EXPECT_NEAR(p.ground_z, e.lo, 1e-9) << e.id;
      double top = -INFINITY;
      for (Vec2 v : p.footprint.outer) top = std::max(top, p.top_at(v));
      EXPECT_LE(top, e.lo + e.height + 1e-9) << e.id;
      EXPECT_GT(top, e.lo + e.eaves + 1) << e.id;
    }
  }
  // A part from 3 m: still no occluder, its box from the lowest ground + 3 to the highest + 10.
  const CityObject& raised = object(c, "raised-part");
  EXPECT_TRUE(raised.occluders.empty());
  EXPECT_NEAR(raised.bbox.zmin, 7.6 + 3, 1e-9);
  EXPECT_NEAR(raised.bbox.zmax, 9.2 + 10, 1e-9);
  EXPECT_EQ(c.report.on_terrain, 4u);
  EXPECT_EQ(c.terrain.triangles.size(), 4u);
}

TEST(GeoJsonOnTerrain, TerrainReadFirst) {
  expect_on_terrain(read_city({data("terrain.city.json"), data("geojson_on_terrain.geojson")}));
}

TEST(GeoJsonOnTerrain, TerrainReadLast) {
  expect_on_terrain(read_city({data("geojson_on_terrain.geojson"), data("terrain.city.json")}));
}

TEST(GeoJsonOnTerrain, WithoutTerrainOnZero) {
  const City c = read_city({data("geojson_on_terrain.geojson")});
  EXPECT_DOUBLE_EQ(object(c, "on-dip").ground_z, 0.0);
  EXPECT_DOUBLE_EQ(occluder_top(c, "on-dip"), 10.0);
  EXPECT_EQ(c.report.on_terrain, 0u);
}

// ---- 4. CityJSON: the top is the lowest point of every upward-facing surface ----

TEST(CityJsonTop, EveryUpwardSurfaceBoundsTheOccluderTop) {
  const City c = read_city({data("cityjson_upward_surfaces.city.json")});
  // Roof at 12 m over half, a terrace (OuterFloorSurface) at 6 m over the other half.
  EXPECT_DOUBLE_EQ(occluder_top(c, "terrace-house"), 6.0);
  EXPECT_NEAR(occluder_area(object(c, "terrace-house")), 100.0, 1e-6);
  // The same with an extension type "+Terrace" at 7 m.
  EXPECT_DOUBLE_EQ(occluder_top(c, "ext-house"), 7.0);
  // A vertical extension surface low on a wall and a downward OuterCeilingSurface (a canopy's
  // underside at 3 m) do not lower the top.
  EXPECT_DOUBLE_EQ(occluder_top(c, "vertical-ext"), 12.0);
  for (const char* id : {"terrace-house", "ext-house", "vertical-ext"})
    EXPECT_DOUBLE_EQ(object(c, id).bbox.zmax, 12.0) << id;
}

// ---- 5. CityJSON: raised parts give no ground-standing occluder ----

TEST(CityJsonRaised, PartsOffTheGroundGiveNoOccluder) {
  const City c = read_city({data("cityjson_raised_parts.city.json")});
  ASSERT_EQ(c.objects.size(), 2u);
  // towers: a tower on the ground (0..10 x 0..10, roof 20 m), a skyway on an
  // OuterCeilingSurface at 10 m (x 10..20) and a bottomless dormer on the tower's roof (20 m).
  const CityObject& towers = object(c, "towers");
  ASSERT_EQ(towers.occluders.size(), 1u);
  EXPECT_DOUBLE_EQ(towers.occluders[0].ground_z, 0.0);
  EXPECT_DOUBLE_EQ(towers.occluders[0].top_z, 20.0);
  EXPECT_NEAR(area(towers.occluders[0].footprint), 100.0, 1e-6);
  // Their surfaces and box stay.
  EXPECT_EQ(towers.surfaces.size(), 6u + 6u + 5u);
  EXPECT_NEAR(towers.bbox.xy.max.x - towers.bbox.xy.min.x, 20.0, 1e-9);
  EXPECT_DOUBLE_EQ(towers.bbox.zmax, 23.0);
  ASSERT_EQ(towers.footprint.size(), 1u);
  EXPECT_NEAR(area(towers.footprint[0]), 100.0, 1e-6);
  // arcade: walls reach the ground only at a pier; its underside is an OuterCeilingSurface at
  // 3 m and it has no GroundSurface: open below, no occluder.
  const CityObject& arcade = object(c, "arcade");
  EXPECT_TRUE(arcade.occluders.empty());
  EXPECT_TRUE(arcade.occludes);
  EXPECT_DOUBLE_EQ(arcade.bbox.zmin, 0.0);
  EXPECT_DOUBLE_EQ(arcade.bbox.zmax, 10.0);
  EXPECT_EQ(c.report.raised_parts, 3u);
}

// ---- 6. CityJSON: a footprint from a roof's projection never includes the overhang ----

TEST(CityJsonOverhang, FootprintIsWhereTheWallsStand) {
  const City c = read_city({data("cityjson_roof_overhang.city.json")});
  // eaves: walls around 0..10 x 0..10, a flat roof at 6 m over -1..11 x -1..11.
  const CityObject& eaves = object(c, "eaves");
  ASSERT_EQ(eaves.occluders.size(), 1u);
  EXPECT_NEAR(area(eaves.occluders[0].footprint), 100.0, 1e-6);
  const Box2 b = occluder_bounds(c, eaves);
  EXPECT_NEAR(b.min.x, 0.0, 1e-6);
  EXPECT_NEAR(b.min.y, 0.0, 1e-6);
  EXPECT_NEAR(b.max.x, 10.0, 1e-6);
  EXPECT_NEAR(b.max.y, 10.0, 1e-6);
  EXPECT_DOUBLE_EQ(eaves.occluders[0].top_z, 6.0);
  EXPECT_NEAR(eaves.bbox.xy.max.x - eaves.bbox.xy.min.x, 12.0, 1e-9);  // the roof is in the box
  // flush: the roof ends at the walls; its projection is the footprint.
  EXPECT_NEAR(occluder_area(object(c, "flush")), 100.0, 1e-6);
  // shelter: a roof on one back wall: no closed outline, no occluder (but still a footprint
  // that keeps view cells out).
  const CityObject& shelter = object(c, "shelter");
  EXPECT_TRUE(shelter.occluders.empty());
  ASSERT_EQ(shelter.footprint.size(), 1u);
  EXPECT_NEAR(area(shelter.footprint[0]), 100.0, 1e-6);
  EXPECT_EQ(c.report.footprints_from_roof, 1u);
  EXPECT_EQ(c.report.footprints_from_walls, 1u);
  EXPECT_EQ(c.report.footprints_unknown, 1u);
}

// ---- 7. CityJSON: installations belong to their building ----

TEST(CityJsonInstallation, JoinsItsBuildingWithoutOccluder) {
  const City c = read_city({data("cityjson_installations.city.json")});
  // house (0..10 x 0..10, 10 m) with a wing (y 10..15, 6 m); a chimney (to 13 m, out to x 11)
  // on the house and a bay window (out to y 16) on the wing.
  ASSERT_EQ(c.objects.size(), 1u);
  const CityObject& house = c.objects[0];
  EXPECT_EQ(house.source_id, "house");
  ASSERT_EQ(house.occluders.size(), 2u);
  EXPECT_DOUBLE_EQ(house.occluders[0].top_z, 10.0);
  EXPECT_DOUBLE_EQ(house.occluders[1].top_z, 6.0);
  EXPECT_NEAR(occluder_area(house), 150.0, 1e-6);
  EXPECT_NEAR(house.bbox.xy.max.x - house.bbox.xy.min.x, 11.0, 1e-9);
  EXPECT_NEAR(house.bbox.xy.max.y - house.bbox.xy.min.y, 16.0, 1e-9);
  EXPECT_DOUBLE_EQ(house.bbox.zmax, 13.0);
  EXPECT_EQ(house.surfaces.size(), 6u + 6u + 5u + 6u);
  EXPECT_EQ(c.report.installations, 2u);
  const std::map<std::string, std::size_t> ignored{{"SolitaryVegetationObject", 1}};
  EXPECT_EQ(c.report.ignored_types, ignored);
}

// ---- 8. Implausible input is refused (exit 18) ----

void expect_implausible(const std::vector<std::string>& files, const std::string& what) {
  try {
    read_city(files);
    ADD_FAILURE() << files.back() << " was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::Implausible) << e.what();
    EXPECT_EQ(exit_code(e.problem()), 18);
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(Implausible, GeoJsonBuilding10kmTall) {
  expect_implausible({data("geojson_too_tall.geojson")}, "way/10000");
}

TEST(Implausible, CityJsonBuilding10kmTall) {
  expect_implausible({data("cityjson_too_tall.city.json")}, "tower-10km");
}

TEST(Implausible, CityJsonVerticesOver5000km) {
  expect_implausible({data("cityjson_too_wide.city.json")}, "span 5000 km");
}

TEST(Implausible, GeoJsonBuildingsOver5000km) {
  expect_implausible({data("geojson_too_wide.geojson")}, "span 5000 km");
}

// ---- 9. CityJSON 1.1 and 2.0 require "transform" ----

TEST(CityJsonTransform, Version11AppliesItsTransform) {
  // Integer vertices, scale 0.001, translate (85100, 446200, -5): a 10 x 10 box from -5 m to
  // 7.5 m whose south-west corner is the frame's origin.
  const City c = read_city({data("cityjson_v11_transform.city.json")});
  const CityObject& o = object(c, "b11");
  EXPECT_DOUBLE_EQ(c.frame.origin[0], 85100.0);
  EXPECT_DOUBLE_EQ(c.frame.origin[1], 446200.0);
  EXPECT_NEAR(o.bbox.xy.min.x, 0.0, 1e-9);
  EXPECT_NEAR(o.bbox.xy.max.x, 10.0, 1e-9);
  EXPECT_NEAR(o.bbox.xy.max.y, 10.0, 1e-9);
  EXPECT_NEAR(o.bbox.zmin, -5.0, 1e-9);
  EXPECT_NEAR(occluder_top(c, "b11"), 7.5, 1e-9);
}

TEST(CityJsonTransform, Version20WithoutTransformIsRefused) {
  try {
    read_city({data("cityjson_v20_without_transform.city.json")});
    FAIL() << "a CityJSON 2.0 file without transform was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::BadStructure);
    EXPECT_EQ(e.feature(), "transform");
    EXPECT_NE(std::string(e.what()).find("requires \"transform\""), std::string::npos);
  }
}

TEST(CityJsonTransform, Version10WithoutTransformIsMetres) {
  const City c = read_city({data("cityjson_v10_without_transform.city.json")});
  EXPECT_NEAR(object(c, "b10").bbox.xy.max.x - object(c, "b10").bbox.xy.min.x, 10.0, 1e-9);
  EXPECT_NEAR(occluder_top(c, "b10"), 10.0, 1e-9);
}

}  // namespace
}  // namespace urbanpvs::geometry
