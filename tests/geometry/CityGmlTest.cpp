// SPDX-License-Identifier: GPL-3.0-or-later
// CityGML input (CityGmlReader.cpp). A hand-made district (tests/data/citygml/two_buildings.gml:
// a gabled LoD2 house whose solid refers to its thematic surfaces by xlink, with a balcony; a
// LoD1 block with a LoD1 building part; a compound reference system) reads as its own numbers
// say, and so does a CityGML 3.0 one (core:boundary, con:*Surface, bldg:buildingPart, a shell
// reused by xlink). The bundled district and, where ../shared/cities has it, the 3D BAG tile,
// written by this test as CityGML 2.0 (surfaces with semantics under their thematic surfaces), read
// exactly as their CityJSON files: the same objects, every coordinate to the last bit. Malformed
// CityGML is refused with the file, line and problem (tests/data/bad/ citygml_*, ReaderTest.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "SameCity.hpp"
#include "SharedCities.hpp"
#include "TextFile.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace {

using namespace urbanpvs::geometry;
using Json = nlohmann::ordered_json;
using urbanpvs::test::expect_same_city;
using urbanpvs::test::read_text;

const std::string kTestData = URBANPVS_TEST_DATA;

const CityObject& object_named(const City& city, const std::string& id) {
  for (const CityObject& o : city.objects)
    if (o.source_id == id) return o;
  throw std::runtime_error("no object " + id);
}

// An object's occluder prisms as (height, footprint area), in increasing order. The test cities'
// coordinates are whole metres, so both are exact.
std::vector<std::pair<double, double>> prisms_of(const CityObject& o) {
  std::vector<std::pair<double, double>> out;
  for (const OccluderPrism& p : o.occluders)
    out.push_back({p.top_z - p.ground_z, area(p.footprint)});
  std::sort(out.begin(), out.end());
  return out;
}

TEST(CityGml, ReadsPartsXlinksAndSemanticsOfAHandMadeDistrict) {
  const City city = read_city({kTestData + "/citygml/two_buildings.gml"}, {});
  EXPECT_EQ(city.frame.crs, "EPSG:25832");  // the horizontal part of the compound system
  ASSERT_EQ(city.objects.size(), 2u);

  // The house: its seven thematic surfaces (each met twice: under boundedBy and by xlink from
  // the solid) once each; the balcony is no part of it.
  const CityObject& house = object_named(city, "DEBY_B1");
  EXPECT_EQ(house.surfaces.size(), 7u);
  const Box3 h = house.bbox;
  EXPECT_DOUBLE_EQ(h.xy.max.x - h.xy.min.x, 10.0);
  EXPECT_DOUBLE_EQ(h.xy.max.y - h.xy.min.y, 8.0);  // the balcony would reach 2 m further south
  EXPECT_DOUBLE_EQ(h.zmax - h.zmin, 9.0);
  ASSERT_EQ(house.occluders.size(), 1u);
  // A prism over the ground surface up to the eaves, the roof's lowest point.
  EXPECT_DOUBLE_EQ(area(house.occluders[0].footprint), 80.0);
  EXPECT_DOUBLE_EQ(house.occluders[0].top_z - house.occluders[0].ground_z, 6.0);

  // The block and its part: one prism each, 12 m and 20 m tall.
  const CityObject& block = object_named(city, "DEBY_B2");
  using Prisms = std::vector<std::pair<double, double>>;
  EXPECT_EQ(prisms_of(block), (Prisms{{12.0, 36.0}, {20.0, 16.0}}));
  EXPECT_DOUBLE_EQ(block.bbox.zmax - block.bbox.zmin, 20.0);
}

TEST(CityGml, ReadsCityGml3BoundariesPartsAndReusedGeometry) {
  const City city = read_city({kTestData + "/citygml/citygml3_parts_and_reuse.gml"}, {});
  EXPECT_EQ(city.frame.crs, "EPSG:25833");
  ASSERT_EQ(city.objects.size(), 3u);
  // The house's six surfaces (the solid names them again, by xlink to a MultiSurface and to
  // thematic surfaces: taken once) and its tower's six.
  const CityObject& house = object_named(city, "house3");
  EXPECT_EQ(house.surfaces.size(), 12u);
  using Prisms = std::vector<std::pair<double, double>>;
  EXPECT_EQ(prisms_of(house), (Prisms{{12.0, 120.0}, {20.0, 16.0}}));
  // The other two buildings are the tower's solid again: the same prism.
  for (const char* id : {"reuse", "reuse_by_property"}) {
    const CityObject& reuse = object_named(city, id);
    EXPECT_EQ(reuse.surfaces.size(), 6u) << id;
    EXPECT_EQ(prisms_of(reuse), (Prisms{{20.0, 16.0}})) << id;
  }
}

// A building with a polygon whose coordinates cannot be read (13 numbers for 3D points) is kept
// as an object that occludes nothing, over the box of what could be read, and the rest of the
// city reads as it does without it; --strict refuses it, naming the building.
TEST(CityGml, UnreadableRingKeepsItsBuildingAsAnObjectThatOccludesNothing) {
  auto box = [](double x0, const std::string& extra) {
    const double x1 = x0 + 10;
    auto ring = [](std::vector<std::array<double, 3>> pts) {
      std::string s = "<gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>";
      for (const auto& p : pts)
        s += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + " ";
      return s + "</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>";
    };
    return "<gml:MultiSurface>" +
           ring({{x0, 0, 0}, {x0, 10, 0}, {x1, 10, 0}, {x1, 0, 0}, {x0, 0, 0}}) +
           ring({{x0, 0, 10}, {x1, 0, 10}, {x1, 10, 10}, {x0, 10, 10}, {x0, 0, 10}}) +
           ring({{x0, 0, 0}, {x1, 0, 0}, {x1, 0, 10}, {x0, 0, 10}, {x0, 0, 0}}) +
           ring({{x1, 0, 0}, {x1, 10, 0}, {x1, 10, 10}, {x1, 0, 10}, {x1, 0, 0}}) +
           ring({{x1, 10, 0}, {x0, 10, 0}, {x0, 10, 10}, {x1, 10, 10}, {x1, 10, 0}}) +
           ring({{x0, 10, 0}, {x0, 0, 0}, {x0, 0, 10}, {x0, 10, 10}, {x0, 10, 0}}) + extra +
           "</gml:MultiSurface>";
  };
  const std::string odd =
      "<gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>20 0 12 21 0 "
      "12 21 1 12 20 0 12 5</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>"
      "</gml:surfaceMember>";
  auto building = [](const std::string& id, const std::string& geometry) {
    return "<cityObjectMember><bldg:Building gml:id=\"" + id + "\"><bldg:lod2MultiSurface>" +
           geometry + "</bldg:lod2MultiSurface></bldg:Building></cityObjectMember>";
  };
  const std::string text =
      "<?xml version=\"1.0\"?><CityModel xmlns=\"http://www.opengis.net/citygml/2.0\" "
      "xmlns:bldg=\"http://www.opengis.net/citygml/building/2.0\" "
      "xmlns:gml=\"http://www.opengis.net/gml\"><gml:boundedBy><gml:Envelope "
      "srsName=\"EPSG:28992\" srsDimension=\"3\"/></gml:boundedBy>" +
      building("good", box(0, "")) + building("odd", box(20, odd)) + "</CityModel>";
  const City city = read_city_text(text, "odd.gml", {});
  ASSERT_EQ(city.objects.size(), 2u);
  EXPECT_TRUE(city.objects[0].occludes);
  EXPECT_EQ(city.objects[1].source_id, "odd");
  EXPECT_FALSE(city.objects[1].occludes);
  EXPECT_TRUE(city.objects[1].occluders.empty());
  EXPECT_DOUBLE_EQ(city.objects[1].bbox.zmax, 10);  // the box of the polygons that could be read
  ASSERT_EQ(city.report.non_occluding.size(), 1u);
  EXPECT_EQ(city.report.non_occluding[0],
            "odd.gml: odd: invalid geometry: a ring's coordinates cannot be read: 13 coordinates "
            "are no whole number of 3D points (kept as an object that occludes nothing)");
  ReadOptions strict;
  strict.strict = true;
  try {
    read_city_text(text, "odd.gml", strict);
    ADD_FAILURE() << "--strict read an unreadable ring";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::InvalidGeometry);
    EXPECT_EQ(e.feature(), "odd");
  }
}

// Such a building stands on the convex hull of the vertices that could be read, not on their
// box: a triangle keeps the other half of its box in free space (a diagonal or long
// ruin does not take the streets beside it out of the view cells).
TEST(CityGml, UnreadableBuildingStandsOnTheHullOfItsVertices) {
  auto polygon = [](const std::string& pos_list) {
    return "<gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>" +
           pos_list +
           "</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>"
           "</gml:surfaceMember>";
  };
  const std::string text =
      "<?xml version=\"1.0\"?><CityModel xmlns=\"http://www.opengis.net/citygml/2.0\" "
      "xmlns:bldg=\"http://www.opengis.net/citygml/building/2.0\" "
      "xmlns:gml=\"http://www.opengis.net/gml\"><gml:boundedBy><gml:Envelope "
      "srsName=\"EPSG:28992\" srsDimension=\"3\"/></gml:boundedBy><cityObjectMember>"
      "<bldg:Building gml:id=\"wedge\"><bldg:lod2MultiSurface><gml:MultiSurface>" +
      polygon("0 0 0 0 20 0 20 0 0 0 0 0") + polygon("0 0 9 20 0 9 0 20 9 0 0 9") +
      polygon("2 2 9 3 2 9 3 3") +
      "</gml:MultiSurface></bldg:lod2MultiSurface></bldg:Building>"
      "</cityObjectMember></CityModel>";
  const City city = read_city_text(text, "wedge.gml", {});
  ASSERT_EQ(city.objects.size(), 1u);
  const CityObject& o = city.objects[0];
  EXPECT_FALSE(o.occludes);
  EXPECT_NEAR(o.bbox.xy.area(), 400, 1e-6);  // tested for visibility over its box
  ASSERT_EQ(o.footprint.size(), 1u);
  EXPECT_NEAR(area(o.footprint[0]), 200, 1e-6);  // free space loses the triangle only
}

TEST(CityGml, GenericAttributesAreWhatPayloadReads) {
  ReadOptions options;
  options.payload_key = "tile";
  const City two = read_city({kTestData + "/citygml/two_buildings.gml"}, options);
  EXPECT_EQ(object_named(two, "DEBY_B1").payload, "tile-17");  // CityGML 2.0
  EXPECT_EQ(object_named(two, "DEBY_B2").payload, "");
  const City three = read_city({kTestData + "/citygml/citygml3_parts_and_reuse.gml"}, options);
  EXPECT_EQ(object_named(three, "house3").payload, "tile-3");  // 3.0, white space trimmed
}

// The German surveying offices' names for their reference systems (AdV), ETRS89 UTM and the
// older DHDN Gauss-Krüger zones (Bavaria's LoD2), and a CityGML 3.0 reference to a local frame
// the file defines: all read; the Gauss-Krüger names were refused as unknown (exit 13).
TEST(CityGml, ReadsAdvNamesAndLocalFrames) {
  auto one_box = [](const std::string& srs, double x, double y) {
    std::string ring = "<gml:posList>";
    for (const auto& [dx, dy, z] : std::vector<std::array<double, 3>>{
             {0, 0, 0}, {0, 10, 0}, {10, 10, 0}, {10, 0, 0}, {0, 0, 0}})
      ring += std::to_string(x + dx) + " " + std::to_string(y + dy) + " " + std::to_string(z) + " ";
    ring += "</gml:posList>";
    return "<?xml version=\"1.0\"?><CityModel xmlns=\"http://www.opengis.net/citygml/2.0\" "
           "xmlns:bldg=\"http://www.opengis.net/citygml/building/2.0\" "
           "xmlns:gml=\"http://www.opengis.net/gml\"><gml:boundedBy><gml:Envelope srsName=\"" +
           srs +
           "\" srsDimension=\"3\"/></gml:boundedBy><cityObjectMember><bldg:Building "
           "gml:id=\"b\"><bldg:measuredHeight>9</bldg:measuredHeight><bldg:lod0FootPrint>"
           "<gml:MultiSurface><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing>" +
           ring +
           "</gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>"
           "</gml:MultiSurface></bldg:lod0FootPrint></bldg:Building></cityObjectMember>"
           "</CityModel>";
  };
  for (const auto& [srs, want] : std::vector<std::pair<std::string, std::string>>{
           {"urn:adv:crs:ETRS89_UTM32*DE_DHHN2016_NH", "EPSG:25832"},
           {"urn:adv:crs:DE_DHDN_3GK4*DE_DHHN92_NH", "EPSG:31468"},
           {"urn:adv:crs:DE_DHDN_3GK3", "EPSG:31467"}}) {
    const City city = read_city_text(one_box(srs, 4468000, 5333000), "adv.gml", {});
    EXPECT_EQ(city.frame.crs, want) << srs;
    EXPECT_EQ(city.frame.kind, LocalFrame::Kind::Projected) << srs;
    ASSERT_EQ(city.objects.size(), 1u) << srs;
  }
  const City local = read_city_text(one_box("#local-CRS-1", 12, 34), "local.gml", {});
  EXPECT_EQ(local.frame.crs, "");
  EXPECT_EQ(local.frame.kind, LocalFrame::Kind::Projected);
  ASSERT_EQ(local.objects.size(), 1u);
  EXPECT_NEAR(local.objects[0].bbox.xy.max.x - local.objects[0].bbox.xy.min.x, 10, 1e-9);
}

TEST(CityGml, TakesLatitudeFirstInEpsg4979) {
  // GML's axis order is the reference system's: latitude, longitude for EPSG:4979.
  const City city = read_city({kTestData + "/citygml/latitude_first_epsg4979.gml"}, {});
  ASSERT_EQ(city.objects.size(), 1u);
  EXPECT_EQ(city.frame.kind, LocalFrame::Kind::Geographic);
  EXPECT_NEAR(city.frame.origin_lat, 47.0, 1e-3);
  EXPECT_NEAR(city.frame.origin_lon, 9.5, 1e-3);
  const CityObject& o = city.objects[0];
  ASSERT_EQ(o.occluders.size(), 1u);
  // 10 x 10 m (swapped axes would give 13.7 x 7.3 m)
  EXPECT_NEAR(o.bbox.xy.max.x - o.bbox.xy.min.x, 10.0, 0.05);
  EXPECT_NEAR(o.bbox.xy.max.y - o.bbox.xy.min.y, 10.0, 0.05);
  EXPECT_NEAR(o.occluders[0].top_z - o.occluders[0].ground_z, 15.0, 1e-6);
}

TEST(CityGml, ReadsTheReliefAsTerrainAndListsOtherObjectsAsIgnored) {
  const City city = read_city({kTestData + "/citygml/building_on_relief.gml"}, {});
  ASSERT_EQ(city.objects.size(), 1u);
  EXPECT_EQ(city.objects[0].source_id, "house");
  ASSERT_EQ(city.terrain.triangles.size(), 2u);
  double lo = 1e9, hi = -1e9;
  for (const Triangle3& t : city.terrain.triangles)
    for (const Vec3& v : t.v) lo = std::min(lo, v.z), hi = std::max(hi, v.z);
  EXPECT_DOUBLE_EQ(hi - lo, 10.0);  // 10 m .. 20 m in the file
  EXPECT_EQ(city.report.ignored_types.at("SolitaryVegetationObject"), 1u);
  EXPECT_EQ(city.report.ignored_types.size(), 1u);
  ASSERT_EQ(city.objects[0].occluders.size(), 1u);
  EXPECT_DOUBLE_EQ(area(city.objects[0].occluders[0].footprint), 100.0);
}

// --- The bundled district as CityGML, written here from its CityJSON ---

std::string number(double v) {
  char s[40];
  std::snprintf(s, sizeof s, "%.17g", v);
  return s;
}

// A CityJSON ring (vertex indices) as a closed gml:LinearRing, the transform applied the way a
// CityJSON reader applies it.
std::string linear_ring(const Json& ring, const Json& doc) {
  const Json& scale = doc["transform"]["scale"];
  const Json& translate = doc["transform"]["translate"];
  std::string points;
  auto add = [&](std::size_t i) {
    const Json& v = doc["vertices"][i];
    for (int k = 0; k < 3; ++k)
      points +=
          number(v[k].get<double>() * scale[k].get<double>() + translate[k].get<double>()) + " ";
  };
  for (const Json& i : ring) add(i.get<std::size_t>());
  add(ring[0].get<std::size_t>());
  points.pop_back();
  return "<gml:LinearRing><gml:posList srsDimension=\"3\">" + points +
         "</gml:posList></gml:LinearRing>";
}

std::string polygon(const Json& surface, const Json& doc) {
  std::string s = "<gml:Polygon><gml:exterior>" + linear_ring(surface[0], doc) + "</gml:exterior>";
  for (std::size_t r = 1; r < surface.size(); ++r)
    s += "<gml:interior>" + linear_ring(surface[r], doc) + "</gml:interior>";
  return s + "</gml:Polygon>";
}

// The geometry the CityJSON reader takes of an object: the finest LoD below 3, else the finest.
const Json* chosen(const Json& o) {
  const Json* best = nullptr;
  double best_key = -1e9;
  for (const Json& g : o["geometry"]) {
    const Json& l = g["lod"];
    const double lod = l.is_number() ? l.get<double>() : std::stod(l.get<std::string>());
    const double key = lod < 3 ? lod + 100 : -lod;
    if (key > best_key) best = &g, best_key = key;
  }
  return best;
}

// One object with its parts nested the way CityGML nests them (consistsOfBuildingPart), with
// the geometry the CityJSON reader takes of it: a surface with semantics under its thematic
// surface (boundedBy), the others in one lodNMultiSurface (lod0FootPrint at LoD0), in file
// order within each.
std::string gml_object(const std::string& id, const Json& doc) {
  const Json& o = doc["CityObjects"][id];
  const std::string tag = o["type"].get<std::string>();
  std::ostringstream s, plain;
  s << "<bldg:" << tag << " gml:id=\"" << id << "\">\n";
  if (const Json* g = o.contains("geometry") ? chosen(o) : nullptr) {
    const Json& l = (*g)["lod"];
    const std::string lod =
        l.is_number() ? std::to_string(l.get<int>()) : l.get<std::string>().substr(0, 1);
    const std::string type = (*g)["type"].get<std::string>();
    EXPECT_TRUE(type == "Solid" || type == "MultiSurface" || type == "CompositeSurface") << id;
    const bool solid = type == "Solid";
    const Json& surfaces = solid ? (*g)["boundaries"][0] : (*g)["boundaries"];
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
      std::string semantic;
      if (g->contains("semantics")) {
        const Json& v = solid ? (*g)["semantics"]["values"][0][k] : (*g)["semantics"]["values"][k];
        if (!v.is_null())
          semantic = (*g)["semantics"]["surfaces"][v.get<std::size_t>()]["type"].get<std::string>();
      }
      if (semantic.empty()) {
        plain << "<gml:surfaceMember>" << polygon(surfaces[k], doc) << "</gml:surfaceMember>";
        continue;
      }
      s << "<bldg:boundedBy><bldg:" << semantic << "><bldg:lod" << lod
        << "MultiSurface><gml:MultiSurface><gml:surfaceMember>" << polygon(surfaces[k], doc)
        << "</gml:surfaceMember></gml:MultiSurface></bldg:lod" << lod
        << "MultiSurface></bldg:" << semantic << "></bldg:boundedBy>\n";
    }
    if (!plain.str().empty()) {
      const std::string property = lod == "0" ? "lod0FootPrint" : "lod" + lod + "MultiSurface";
      s << "<bldg:" << property << "><gml:MultiSurface>" << plain.str()
        << "</gml:MultiSurface></bldg:" << property << ">\n";
    }
  }
  if (o.contains("children"))
    for (const Json& child : o["children"])
      s << "<bldg:consistsOfBuildingPart>" << gml_object(child.get<std::string>(), doc)
        << "</bldg:consistsOfBuildingPart>\n";
  s << "</bldg:" << tag << ">\n";
  return s.str();
}

std::string as_citygml(const Json& doc) {
  std::ostringstream s;
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       "<core:CityModel xmlns:core=\"http://www.opengis.net/citygml/2.0\" "
       "xmlns:bldg=\"http://www.opengis.net/citygml/building/2.0\" "
       "xmlns:gml=\"http://www.opengis.net/gml\">\n"
       "<gml:boundedBy><gml:Envelope srsName=\""
    << doc["metadata"]["referenceSystem"].get<std::string>()
    << "\" srsDimension=\"3\"></gml:Envelope></gml:boundedBy>\n";
  for (const auto& [id, o] : doc["CityObjects"].items())
    if (!o.contains("parents"))
      s << "<core:cityObjectMember>" << gml_object(id, doc) << "</core:cityObjectMember>\n";
  s << "</core:CityModel>\n";
  return s.str();
}

void check_citygml_of(const std::string& path) {
  const std::string text = read_text(path);
  const Json doc = Json::parse(text);
  const City want = read_city_text(text, "city.city.json", {});
  const City got = read_city_text(as_citygml(doc), "city.gml", {});
  expect_same_city(want, got);
  EXPECT_EQ(got.report.ignored_types, want.report.ignored_types);
  EXPECT_EQ(got.report.repairs.size(), want.report.repairs.size());
  EXPECT_GT(want.objects.size(), 300u);
}

TEST(CityGml, TheBundledDistrictReadsAsItsCityJson) {
  check_citygml_of(std::string(URBANPVS_SOURCE_DIR) + "/cities/sample/district.city.json");
}

TEST(CityGml, TuDelft3dBagTileReadsAsItsCityJson) {
  REQUIRE_SHARED_CITY(path, "tudelft_3dbag_tile5910.city.json");
  check_citygml_of(path);
}

}  // namespace
