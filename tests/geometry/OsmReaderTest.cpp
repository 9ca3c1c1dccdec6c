// SPDX-License-Identifier: GPL-3.0-or-later
// The OpenStreetMap reader (libosmium): a small OSM XML file written here covers each tag and
// assembly case; the real Helsinki extract must give the same buildings as its own GeoJSON
// export (ids, footprints within 1 cm, heights), and every OSM extract in the shared cities
// loads with the defaults.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <osmium/io/xml_input.hpp>
#include <osmium/osm.hpp>
#include <set>
#include <string>

#include "SharedCities.hpp"
#include "urbanpvs/geometry/cells/StreetRegion.hpp"
#include "urbanpvs/geometry/cells/ViewCells.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"

namespace {

using namespace urbanpvs::geometry;
namespace fs = std::filesystem;

using urbanpvs::test::kSharedCities;

std::string write_temp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("urbanpvs_osm_" + name);
  std::ofstream(p) << text;
  return p.string();
}

// Nodes on a 1e-4 degree lattice near Helsinki: node (i, j) has id 1000 + 100 i + j.
std::string node(int i, int j) {
  char s[160];
  std::snprintf(s, sizeof s, "  <node id=\"%d\" version=\"1\" lat=\"%.7f\" lon=\"%.7f\"/>\n",
                1000 + 100 * i + j, 60.17 + 1e-4 * j, 24.94 + 2e-4 * i);
  return s;
}

std::string nd(int i, int j) {
  return "    <nd ref=\"" + std::to_string(1000 + 100 * i + j) + "\"/>\n";
}

std::string way(int id, std::initializer_list<std::pair<int, int>> ring, const std::string& tags) {
  std::string s = "  <way id=\"" + std::to_string(id) + "\" version=\"1\">\n";
  for (auto [i, j] : ring) s += nd(i, j);
  return s + tags + "  </way>\n";
}

std::string tag(const std::string& k, const std::string& v) {
  return "    <tag k=\"" + k + "\" v=\"" + v + "\"/>\n";
}

std::string relation(int id, const std::string& members, const std::string& tags) {
  return "  <relation id=\"" + std::to_string(id) + "\" version=\"1\">\n" + members + tags +
         "  </relation>\n";
}

std::string member(int way_id, const char* role) {
  return "    <member type=\"way\" ref=\"" + std::to_string(way_id) + "\" role=\"" + role +
         "\"/>\n";
}

// How the elements of sample_osm() are ordered.
enum class Order {
  Sorted,  ///< as OSM files are: nodes, ways, relations, each by ascending id
  /// as Overpass API exports are ("out body; >; out skel qt;"): the ways before their nodes,
  /// and each kind in an order of its own (here descending ids); one node also comes twice,
  /// its older version misplaced by 1 km
  Overpass,
  /// the ways, ascending, before the nodes, ascending: only the kinds out of order
  WaysFirst,
};

std::string sample_osm(Order order = Order::Sorted) {
  std::string nodes, s;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 12; ++j)
      nodes = order == Order::Overpass ? node(i, j) + nodes : nodes + node(i, j);
  if (order == Order::Overpass)
    nodes += "  <node id=\"1000\" version=\"0\" lat=\"60.18\" lon=\"24.94\"/>\n";
  std::vector<std::string> ways, relations;
  auto add = [](std::vector<std::string>& to, std::string element) {
    to.push_back(std::move(element));
  };
  // A building with a height in metres and a unit.
  add(ways, way(1, {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}},
                tag("building", "yes") + tag("height", "12 m") + tag("ref:tile", "tiles/7")));
  // Height from levels: 4 x 3 m.
  add(ways, way(2, {{2, 0}, {3, 0}, {3, 1}, {2, 1}, {2, 0}},
                tag("building", "apartments") + tag("building:levels", "4")));
  // Not a building.
  add(ways, way(3, {{4, 0}, {5, 0}, {5, 1}, {4, 1}, {4, 0}}, tag("building", "no")));
  // A building with a part of it standing higher.
  add(ways, way(4, {{6, 0}, {9, 0}, {9, 2}, {6, 2}, {6, 0}},
                tag("building", "yes") + tag("height", "9")));
  add(ways, way(5, {{7, 0}, {8, 0}, {8, 1}, {7, 1}, {7, 0}},
                tag("building:part", "yes") + tag("height", "30") + tag("ref:tile", "part-only")));
  // The outer and inner ways of a courtyard multipolygon (tags on the relation).
  add(ways, way(10, {{0, 3}, {4, 3}, {4, 7}, {0, 7}, {0, 3}}, ""));
  add(ways, way(11, {{1, 4}, {1, 6}, {3, 6}, {3, 4}, {1, 4}}, ""));
  // The only outer way of a multipolygon, not closed: osmium cannot assemble it.
  add(ways, way(12, {{6, 4}, {8, 4}, {8, 6}, {6, 6}}, ""));
  // Streets: a residential street 8 m wide, a footway of its class's width (3 m), a street
  // under construction (no street yet) and a pedestrian zone mapped as an area.
  add(ways, way(30, {{0, 8}, {9, 8}}, tag("highway", "residential") + tag("width", "8 m")));
  add(ways, way(31, {{0, 9}, {3, 9}}, tag("highway", "footway")));
  add(ways, way(32, {{5, 9}, {9, 9}}, tag("highway", "construction")));
  add(ways, way(33, {{5, 10}, {7, 10}, {7, 11}, {5, 11}, {5, 10}},
                tag("highway", "pedestrian") + tag("area", "yes")));
  const std::string mp = tag("type", "multipolygon") + tag("building", "yes");
  add(relations, relation(20, member(10, "outer") + member(11, "inner"),
                          mp + tag("height", "20") + tag("ref:tile", "court")));
  add(relations, relation(21, member(12, "outer"), mp));
  // A member way outside the extract.
  add(relations, relation(22, member(999, "outer"), mp));
  if (order == Order::Overpass) {
    std::reverse(ways.begin(), ways.end());
    std::reverse(relations.begin(), relations.end());
  }
  for (const std::string& w : ways) s += w;
  s = order == Order::Sorted ? nodes + s : s + nodes;
  for (const std::string& r : relations) s += r;
  return "<?xml version=\"1.0\"?>\n<osm version=\"0.6\" generator=\"test\">\n" + s + "</osm>\n";
}

const CityObject* find(const City& c, const std::string& id) {
  for (const CityObject& o : c.objects)
    if (o.source_id == id) return &o;
  return nullptr;
}

bool mentions(const std::vector<std::string>& lines, const std::string& a, const std::string& b) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) {
    return l.find(a) != std::string::npos && l.find(b) != std::string::npos;
  });
}

TEST(OsmReader, TagsIdsMultipolygonsAndPartsFromOsmXml) {
  const std::string path = write_temp("sample.osm", sample_osm());
  ReadOptions options;
  options.default_height = 10;
  const City city = read_city({path}, options);
  ASSERT_EQ(city.frame.kind, LocalFrame::Kind::Geographic);
  // w1, w2, r20 and w4 (with its part w5), and r21, which cannot be assembled, kept; building=no
  // and r22, of which nothing lies in the file, are not there.
  std::vector<std::string> ids;
  for (const CityObject& o : city.objects) ids.push_back(o.source_id);
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<std::string>{"r20", "r21", "w1", "w2", "w4"}));
  EXPECT_FALSE(find(city, "r21")->occludes);

  EXPECT_NEAR(find(city, "w1")->bbox.zmax, 12, 1e-9);
  EXPECT_NEAR(find(city, "w2")->bbox.zmax, 12, 1e-9);  // 4 levels x 3 m
  EXPECT_NEAR(find(city, "w4")->bbox.zmax, 30, 1e-9);  // its part reaches 30 m
  const CityObject* courtyard = find(city, "r20");
  ASSERT_EQ(courtyard->footprint.size(), 1u);
  ASSERT_EQ(courtyard->footprint[0].holes.size(), 1u);
  // Outer 4 x 4 cells of the lattice, inner 2 x 2: three quarters of the outer area is left.
  const double outer = area(Polygon{courtyard->footprint[0].outer, {}});
  EXPECT_NEAR(area(courtyard->footprint[0]), outer * 0.75, outer * 1e-6);
  EXPECT_NEAR(courtyard->bbox.zmax, 20, 1e-9);

  // The assembly problems are reported per element.
  EXPECT_TRUE(mentions(city.report.warnings, "r21", "")) << "unclosed ring of r21";
  EXPECT_TRUE(mentions(city.report.warnings, "r22", "outside the extract"));
  fs::remove(path);
}

// A building osmium's area assembler cannot build is still a building: closed rings (a way's, or
// a multipolygon's whose rings touch at a point that is no node) are mended by the ring repair
// and occlude; what cannot be mended (members or nodes outside the extract, an open way, a
// multipolygon whose ways do not close up) is kept as an object
// that occludes nothing over the box of its nodes in the file, as tall as its tags say or, without
// them, as a building may be; the convex hull of those nodes, not their box, is its footprint
// (what leaves free space). Nodes that span no area (a building's corner) are no building.
TEST(OsmReader, BuildingsTheAssemblerCannotBuildAreKept) {
  std::string s;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 12; ++j)
      if (!(i == 9 && j == 11)) s += node(i, j);  // node 1911 lies outside the extract
  // A bow-tie: its two crossing edges give two triangles, (0,0)-(1,1)-(0,2) and (2,0)-(1,1)-(2,2).
  s += way(40, {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {0, 0}},
           tag("building", "yes") + tag("height", "8"));
  // A square with a spike out to (5,0) and back.
  s += way(41, {{3, 0}, {4, 0}, {5, 0}, {4, 0}, {4, 1}, {3, 1}, {3, 0}},
           tag("building", "yes") + tag("height", "8"));
  // Two outer rings, the second touching the first's edge at (6,4), which is no node of it.
  s += way(42, {{4, 3}, {6, 3}, {6, 5}, {4, 5}, {4, 3}}, "");
  s += way(43, {{6, 4}, {8, 3}, {8, 5}, {6, 4}}, "");
  // An open building way.
  s += way(44, {{0, 8}, {2, 8}, {2, 10}}, tag("building", "yes"));
  // A closed way whose first and last node lie outside the extract: the others span its box.
  s += way(45, {{9, 11}, {9, 9}, {7, 9}, {7, 11}, {9, 11}}, tag("building", "yes"));
  // A building way of which only two nodes lie in the extract, on one line of the lattice.
  s += way(47, {{9, 11}, {9, 7}, {9, 6}, {9, 11}}, tag("building", "yes"));
  // A multipolygon whose two ways leave a gap: no ring.
  s += way(48, {{0, 3}, {2, 3}, {2, 5}}, "");
  s += way(49, {{2, 5}, {0, 5}, {0, 4}}, "");
  // A multipolygon with one member in the file and one outside it.
  s += way(46, {{4, 8}, {6, 8}, {6, 10}, {4, 10}, {4, 8}}, "");
  const std::string mp = tag("type", "multipolygon") + tag("building", "yes");
  s += relation(50, member(42, "outer") + member(43, "outer"), mp + tag("height", "15"));
  s += relation(51, member(46, "outer") + member(998, "outer"), mp);
  s += relation(52, member(48, "outer") + member(49, "outer"), mp);
  const std::string path = write_temp(
      "unbuilt.osm", "<?xml version=\"1.0\"?>\n<osm version=\"0.6\">\n" + s + "</osm>\n");
  ReadOptions options;
  options.max_height = 90;
  const City city = read_city({path}, options);
  std::vector<std::string> ids;
  for (const CityObject& o : city.objects) ids.push_back(o.source_id);
  std::sort(ids.begin(), ids.end());
  ASSERT_EQ(ids, (std::vector<std::string>{"r50", "r51", "r52", "w40", "w41", "w44", "w45"}));
  EXPECT_TRUE(mentions(city.report.warnings, "w47", "span no area"));

  // The lattice's cells in metres, from the repaired squares' own sizes.
  const CityObject* spiked = find(city, "w41");
  ASSERT_TRUE(spiked->occludes);
  ASSERT_EQ(spiked->footprint.size(), 1u);
  const Box2 cell = bounds(spiked->footprint[0]);  // the spike is gone: one lattice cell
  const double cell_area = cell.area();
  EXPECT_NEAR(area(spiked->footprint[0]), cell_area, 1e-4 * cell_area);
  EXPECT_NEAR(spiked->bbox.zmax, 8, 1e-9);
  const CityObject* bowtie = find(city, "w40");
  ASSERT_TRUE(bowtie->occludes);
  double bowtie_area = 0;
  for (const Polygon& p : bowtie->footprint) bowtie_area += area(p);
  EXPECT_NEAR(bowtie_area, 2 * cell_area, 0.01 * cell_area);  // two triangles of 1 cell each
  // The touching rings: a square of 2 x 2 cells and a triangle of 2 cells, 15 m tall.
  const CityObject* touching = find(city, "r50");
  ASSERT_TRUE(touching->occludes);
  double touching_area = 0;
  for (const Polygon& p : touching->footprint) touching_area += area(p);
  EXPECT_NEAR(touching_area, 6 * cell_area, 0.01 * cell_area);
  EXPECT_NEAR(touching->bbox.zmax, 15, 1e-9);

  // The rest occlude nothing, stand as tall as a building may be, and cover their nodes.
  const auto nodes_box = [&](int i0, int j0, int i1, int j1) {
    Box2 b;
    for (const CityObject& o : city.objects)  // w41's lattice cell (3..4, 0..1), shifted
      if (o.source_id == "w41") b = bounds(o.footprint[0]);
    const Vec2 size = b.max - b.min;
    const Vec2 at = b.min - Vec2{3 * size.x, 0};  // lattice point (0, 0)
    Box2 out;
    out.extend(at + Vec2{i0 * size.x, j0 * size.y});
    out.extend(at + Vec2{i1 * size.x, j1 * size.y});
    return out;
  };
  struct Expect {
    const char* id;
    Box2 box;
    double height;
    const char* why;
    double hull_cells;  // the convex hull of its nodes in the file, in lattice cells
  };
  for (const Expect& e :
       {Expect{"r52", nodes_box(0, 3, 2, 5), 90, "do not form rings", 4},
        Expect{"r51", nodes_box(4, 8, 6, 10), 90, "members outside the extract", 4},
        Expect{"w44", nodes_box(0, 8, 2, 10), 90, "an open way", 2},  // a triangle, half its box
        Expect{"w45", nodes_box(7, 9, 9, 11), 90, "outside the extract", 2}}) {
    SCOPED_TRACE(e.id);
    const CityObject* o = find(city, e.id);
    EXPECT_FALSE(o->occludes);
    EXPECT_TRUE(o->occluders.empty());
    EXPECT_NEAR(o->bbox.zmax - o->ground_z, e.height, 1e-9);
    EXPECT_NEAR(o->bbox.xy.min.x, e.box.min.x, 0.05);
    EXPECT_NEAR(o->bbox.xy.max.x, e.box.max.x, 0.05);
    EXPECT_NEAR(o->bbox.xy.min.y, e.box.min.y, 0.05);
    EXPECT_NEAR(o->bbox.xy.max.y, e.box.max.y, 0.05);
    ASSERT_EQ(o->footprint.size(), 1u);
    EXPECT_NEAR(area(o->footprint[0]), e.hull_cells * cell_area, 0.01 * cell_area);
    EXPECT_TRUE(mentions(city.report.non_occluding, std::string(e.id) + ": ", e.why));
  }
  options.strict = true;
  try {
    read_city({path}, options);
    FAIL() << "--strict accepted buildings that cannot be built";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::InvalidGeometry);
    EXPECT_EQ(e.file(), path);
  }
  fs::remove(path);
}

// A multipolygon osmium refuses (one of its outer rings is a bow-tie) is repaired as outer rings
// less inner ones, and an outer ring on an island in a courtyard keeps its area: the courtyard's
// ring is no hole of it.
TEST(OsmReader, UnbuiltMultipolygonKeepsItsCourtyardAndTheIslandInIt) {
  std::string s;
  for (int i = 0; i <= 12; ++i)
    for (int j = 0; j <= 9; ++j) s += node(i, j);
  s += way(70, {{0, 0}, {9, 0}, {9, 9}, {0, 9}, {0, 0}}, "");       // 81 cells
  s += way(71, {{3, 3}, {6, 3}, {6, 6}, {3, 6}, {3, 3}}, "");       // the courtyard: 9 cells
  s += way(72, {{4, 4}, {5, 4}, {5, 5}, {4, 5}, {4, 4}}, "");       // the island: 1 cell
  s += way(73, {{10, 0}, {12, 2}, {12, 0}, {10, 2}, {10, 0}}, "");  // a bow-tie: 2 cells
  s += relation(
      80, member(70, "outer") + member(71, "inner") + member(72, "outer") + member(73, "outer"),
      tag("type", "multipolygon") + tag("building", "yes") + tag("height", "20"));
  const std::string path =
      write_temp("island.osm", "<?xml version=\"1.0\"?>\n<osm version=\"0.6\">\n" + s + "</osm>\n");
  const City city = read_city({path});
  ASSERT_EQ(city.objects.size(), 1u);
  const CityObject& o = city.objects[0];
  ASSERT_TRUE(o.occludes) << "r80 is kept as an object that occludes nothing";
  const double cell = o.bbox.xy.area() / (12 * 9);
  double footprint = 0;
  for (const Polygon& p : o.footprint) footprint += area(p);
  EXPECT_NEAR(footprint, (81 - 9 + 1 + 2) * cell, 0.2 * cell);
  fs::remove(path);
}

// Two OSM files, one with streets and no building: OpenStreetMap is WGS84 whatever a file holds,
// so the pair is read in either order (it was refused: "OGC:CRS84 differs from ...'s (none)").
TEST(OsmReader, AFileWithoutBuildingsJoinsTheOthers) {
  std::string nodes;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 12; ++j) nodes += node(i, j);
  const auto file = [&](const std::string& name, const std::string& ways) {
    return write_temp(
        name, "<?xml version=\"1.0\"?>\n<osm version=\"0.6\">\n" + nodes + ways + "</osm>\n");
  };
  const std::string streets =
      file("streets_only.osm", way(60, {{0, 8}, {9, 8}}, tag("highway", "residential")));
  const std::string buildings =
      file("buildings_only.osm", way(61, {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}},
                                     tag("building", "yes") + tag("height", "9")));
  for (const auto& paths : {std::vector{streets, buildings}, std::vector{buildings, streets}}) {
    SCOPED_TRACE(paths.front());
    const City city = read_city(paths);
    ASSERT_EQ(city.objects.size(), 1u);
    EXPECT_EQ(city.objects[0].source_id, "w61");
    EXPECT_EQ(city.frame.kind, LocalFrame::Kind::Geographic);
    ASSERT_EQ(city.streets.lines.size(), 1u);
    // The street runs 8 lattice rows north of the building, in the same frame.
    EXPECT_GT(city.streets.lines[0].points.front().y, city.objects[0].bbox.xy.max.y + 50);
    EXPECT_LT(city.streets.lines[0].points.front().y, city.objects[0].bbox.xy.max.y + 100);
  }
  try {
    read_city({streets});
    FAIL() << "a city without buildings accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::EmptyCity);
  }
  fs::remove(streets);
  fs::remove(buildings);
}

// A file saved from JOSM before upload numbers every element negatively: the same city, its
// ids with their sign. With an index of positive node ids alone, every building vanished (the
// "no building found" of citygml-osm's Issue_70.osm and OSM2World's mp_two_outer_roof.osm).
TEST(OsmReader, NegativeIdsAsEditorsSaveThem) {
  const std::string positive_path = write_temp("positive.osm", sample_osm());
  std::string text = sample_osm();
  for (const std::string attribute : {" id=\"", " ref=\""})
    for (std::size_t at = text.find(attribute); at != std::string::npos;
         at = text.find(attribute, at + attribute.size() + 1))
      text.insert(at + attribute.size(), "-");
  const std::string negative_path = write_temp("negative.osm", text);
  ReadOptions options;
  options.default_height = 10;
  const City positive = read_city({positive_path}, options);
  const City negative = read_city({negative_path}, options);
  ASSERT_EQ(negative.objects.size(), positive.objects.size());
  for (const CityObject& o : positive.objects) {
    const std::string id = o.source_id.substr(0, 1) + "-" + o.source_id.substr(1);
    const CityObject* same = find(negative, id);
    ASSERT_NE(same, nullptr) << id;
    EXPECT_EQ(same->bbox.zmax, o.bbox.zmax) << id;
    ASSERT_EQ(same->footprint.size(), o.footprint.size()) << id;
    for (std::size_t k = 0; k < o.footprint.size(); ++k)
      EXPECT_NEAR(area(same->footprint[k]), area(o.footprint[k]), 1e-9) << id;
  }
  fs::remove(positive_path);
  fs::remove(negative_path);
}

// An Overpass API export is read as the same data sorted: every building, part, multipolygon
// and street the same, the newest version of a node that comes twice, and a warning.
TEST(OsmReader, UnsortedOverpassExportGivesTheCityOfTheSortedFile) {
  const std::string sorted_path = write_temp("sorted.osm", sample_osm());
  ReadOptions options;
  options.default_height = 10;
  const City sorted = read_city({sorted_path}, options);
  EXPECT_FALSE(mentions(sorted.report.warnings, sorted_path, "not sorted"));
  for (const Order order : {Order::Overpass, Order::WaysFirst}) {
    SCOPED_TRACE(order == Order::Overpass ? "Overpass order" : "ways first");
    const std::string overpass_path = write_temp("overpass.osm", sample_osm(order));
    const City overpass = read_city({overpass_path}, options);
    ASSERT_EQ(overpass.objects.size(), sorted.objects.size());
    EXPECT_EQ(overpass.frame.origin_lat, sorted.frame.origin_lat);
    EXPECT_EQ(overpass.frame.origin_lon, sorted.frame.origin_lon);
    for (const CityObject& o : sorted.objects) {
      const CityObject* same = find(overpass, o.source_id);
      ASSERT_NE(same, nullptr) << o.source_id;
      EXPECT_EQ(same->bbox.zmax, o.bbox.zmax) << o.source_id;
      ASSERT_EQ(same->footprint.size(), o.footprint.size()) << o.source_id;
      for (std::size_t k = 0; k < o.footprint.size(); ++k)
        EXPECT_EQ(area(same->footprint[k]), area(o.footprint[k])) << o.source_id;
      EXPECT_EQ(same->bbox.xy.min.x, o.bbox.xy.min.x) << o.source_id;
      EXPECT_EQ(same->bbox.xy.max.y, o.bbox.xy.max.y) << o.source_id;
    }
    EXPECT_EQ(overpass.streets.lines.size(), sorted.streets.lines.size());
    EXPECT_EQ(overpass.streets.areas.size(), sorted.streets.areas.size());
    EXPECT_TRUE(mentions(overpass.report.warnings, overpass_path, "not sorted by type and id"));
    // The assembly's own reports are there once, not twice (the streaming attempt is dropped).
    EXPECT_EQ(
        std::count_if(overpass.report.warnings.begin(), overpass.report.warnings.end(),
                      [](const std::string& w) { return w.find("r22") != std::string::npos; }),
        1);
    fs::remove(overpass_path);
  }
  fs::remove(sorted_path);
}

// The OSM XML file at `osm_path` written as the Overpass API writes JSON, by osmium's reading of
// it. `geometry`: as "out geom" gives it: no node elements, each way with the "geometry" of its
// nodes, and the untagged ways that only relations use given inside them by their geometry alone.
std::string overpass_json(const std::string& osm_path, bool geometry) {
  using nlohmann::json;
  const osmium::memory::Buffer buffer = osmium::io::read_file(osm_path);
  std::map<osmium::object_id_type, json> at;  // node id -> {"lat", "lon"}
  for (const auto& n : buffer.select<osmium::Node>())
    at[n.id()] = {{"lat", n.location().lat()}, {"lon", n.location().lon()}};
  auto tags = [](const osmium::OSMObject& o) {
    json t = json::object();
    for (const osmium::Tag& tag : o.tags()) t[tag.key()] = tag.value();
    return t;
  };
  auto way_geometry = [&](const osmium::Way& w) {
    json g = json::array();
    for (const osmium::NodeRef& r : w.nodes())
      g.push_back(at.count(r.ref()) ? at[r.ref()] : json());
    return g;
  };
  std::map<osmium::object_id_type, const osmium::Way*> ways;
  for (const auto& w : buffer.select<osmium::Way>()) ways[w.id()] = &w;
  std::set<osmium::object_id_type> only_in_relations;
  json elements = json::array();
  for (const auto& o : buffer.select<osmium::OSMObject>()) {
    json e = {{"type", osmium::item_type_to_name(o.type())}, {"id", o.id()}};
    if (!o.tags().empty()) e["tags"] = tags(o);
    if (o.type() == osmium::item_type::node) {
      if (geometry) continue;
      const auto& n = static_cast<const osmium::Node&>(o);
      e["lat"] = n.location().lat();
      e["lon"] = n.location().lon();
    } else if (o.type() == osmium::item_type::way) {
      const auto& w = static_cast<const osmium::Way&>(o);
      if (geometry && w.tags().empty()) {
        only_in_relations.insert(w.id());
        continue;
      }
      e["nodes"] = json::array();
      for (const osmium::NodeRef& r : w.nodes()) e["nodes"].push_back(r.ref());
      if (geometry) e["geometry"] = way_geometry(w);
    } else {
      e["members"] = json::array();
      for (const osmium::RelationMember& m : static_cast<const osmium::Relation&>(o).members()) {
        json member = {
            {"type", osmium::item_type_to_name(m.type())}, {"ref", m.ref()}, {"role", m.role()}};
        if (geometry && only_in_relations.count(m.ref()) && ways.count(m.ref()))
          member["geometry"] = way_geometry(*ways[m.ref()]);
        e["members"].push_back(std::move(member));
      }
    }
    elements.push_back(std::move(e));
  }
  return json{{"version", 0.6}, {"generator", "Overpass API"}, {"elements", elements}}.dump(1);
}

// Overpass JSON, with nodes ("out body; >; out skel qt;") or with geometry inline ("out
// geom"), gives the city of the same data as an OSM file: every building, part, multipolygon
// and street, the same footprints and heights, and the same problems.
TEST(OsmReader, OverpassJsonGivesTheCityOfTheOsmFile) {
  const std::string osm_path = write_temp("overpass_source.osm", sample_osm());
  ReadOptions options;
  options.default_height = 10;
  const City from_osm = read_city({osm_path}, options);
  for (const bool geometry : {false, true}) {
    SCOPED_TRACE(geometry ? "out geom" : "out body");
    const std::string path = write_temp("overpass.json", overpass_json(osm_path, geometry));
    const City city = read_city({path}, options);
    ASSERT_EQ(city.objects.size(), from_osm.objects.size());
    for (const CityObject& o : from_osm.objects) {
      const CityObject* same = find(city, o.source_id);
      ASSERT_NE(same, nullptr) << o.source_id;
      EXPECT_EQ(same->bbox.zmax, o.bbox.zmax) << o.source_id;
      ASSERT_EQ(same->footprint.size(), o.footprint.size()) << o.source_id;
      for (std::size_t k = 0; k < o.footprint.size(); ++k) {
        EXPECT_NEAR(area(same->footprint[k]), area(o.footprint[k]), 1e-6) << o.source_id;
        EXPECT_EQ(same->footprint[k].holes.size(), o.footprint[k].holes.size()) << o.source_id;
      }
      EXPECT_NEAR(same->bbox.xy.min.x, o.bbox.xy.min.x, 1e-6) << o.source_id;
      EXPECT_NEAR(same->bbox.xy.max.y, o.bbox.xy.max.y, 1e-6) << o.source_id;
    }
    EXPECT_EQ(city.streets.lines.size(), from_osm.streets.lines.size());
    EXPECT_EQ(city.streets.areas.size(), from_osm.streets.areas.size());
    EXPECT_TRUE(mentions(city.report.warnings, "r21", "")) << "unclosed ring of r21";
    EXPECT_TRUE(mentions(city.report.warnings, "r22", "outside the extract"));
    fs::remove(path);
  }
  fs::remove(osm_path);
}

TEST(OsmReader, BrokenOverpassJsonIsRefusedNamingTheElement) {
  auto refusal = [](const std::string& elements) {
    try {
      read_city_text("{\"generator\": \"Overpass API\", \"elements\": " + elements + "}", "q.json",
                     {});
    } catch (const InputError& e) {
      EXPECT_EQ(e.problem(), InputProblem::BadStructure);
      EXPECT_EQ(e.file(), "q.json");
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal(R"([{"type": "node", "lat": 1, "lon": 2}])"),
            "q.json: elements[0]: unexpected structure: is not an object with a \"type\" and an "
            "integer \"id\"");
  EXPECT_NE(refusal(R"([{"type": "node", "id": 1, "lat": 1, "lon": 2},
                         {"type": "way", "id": 5, "tags": {"building": "yes"}}])")
                .find("elements[1]: unexpected structure: way without a \"nodes\" array: the "
                      "query wrote no geometry"),
            std::string::npos);
  EXPECT_NE(
      refusal(R"([{"type": "node", "id": 1, "lat": 100, "lon": 2}])").find("lat/lon out of range"),
      std::string::npos);
  // Ids beyond what OSM uses are refused before new nodes are numbered above them.
  EXPECT_NE(refusal(R"([{"type": "node", "id": 9223372036854775807, "lat": 1, "lon": 2}])")
                .find("elements[0]: unexpected structure: id is not an integer below 2^60 in size: "
                      "9223372036854775807"),
            std::string::npos);
  EXPECT_NE(refusal(R"([{"type": "way", "id": 5, "nodes": [18446744073709551615]}])")
                .find("node id is not an integer below 2^60"),
            std::string::npos);
  EXPECT_NE(refusal(R"([{"type": "way", "id": 5, "nodes": [1, 2], "geometry": [null]}])")
                .find("one position per node"),
            std::string::npos);
}

TEST(OsmReader, PayloadIsTheNamedTagOfTheBuilding) {
  const std::string path = write_temp("payload.osm", sample_osm());
  ReadOptions options;
  options.default_height = 10;
  options.payload_key = "ref:tile";
  const City city = read_city({path}, options);
  EXPECT_EQ(city.payload_key, "ref:tile");
  EXPECT_EQ(find(city, "w1")->payload, "tiles/7");
  EXPECT_EQ(find(city, "r20")->payload, "court");  // a multipolygon's tag is on its relation
  EXPECT_EQ(find(city, "w2")->payload, "");
  EXPECT_EQ(find(city, "w4")->payload, "");  // its part's tag is not the building's
  options.payload_key.clear();
  for (const CityObject& o : read_city({path}, options).objects) EXPECT_EQ(o.payload, "");
  fs::remove(path);
}

// East-west distance between lattice columns i0 and i1 on row j (about 11.07 m a column).
double street_length(int i0, int i1, int j) {
  return 2e-4 * (i1 - i0) * 111320.0 * std::cos((60.17 + 1e-4 * j) * std::numbers::pi / 180);
}

TEST(OsmReader, StreetsAreHighwaysBufferedByTheirWidthAndStreetAreas) {
  const std::string path = write_temp("streets.osm", sample_osm());
  ReadOptions options;
  options.default_height = 10;
  const City city = read_city({path}, options);
  fs::remove(path);
  // The two streets with their widths (the one under construction is none yet), the zone.
  ASSERT_EQ(city.streets.lines.size(), 2u);
  EXPECT_EQ(city.streets.lines[0].id, "w30");
  EXPECT_EQ(city.streets.lines[0].width, 8);
  EXPECT_EQ(city.streets.lines[1].id, "w31");
  EXPECT_EQ(city.streets.lines[1].width, 3);  // a footway's class width
  ASSERT_EQ(city.streets.areas.size(), 1u);
  // The region: three disjoint pieces, the residential street, the footway, the zone.
  const std::vector<Polygon> region = street_region(city.streets);
  ASSERT_EQ(region.size(), 3u);
  std::vector<double> areas;
  for (const Polygon& p : region) areas.push_back(area(p));
  std::sort(areas.begin(), areas.end());
  // Length x width plus the two half octagons at the ends (an octagon whose sides are h from
  // its centre has 8 tan(π/8) h²); the footway's strip is the region's minimum width, 6 m.
  const double octagon = 8 * std::tan(std::numbers::pi / 8);
  const double residential = street_length(0, 9, 8) * 8 + octagon * 16;
  const double footway = street_length(0, 3, 9) * 6 + octagon * 9;
  const double zone = street_length(5, 7, 10) * (1e-4 * 111320.0 * 1.0);
  EXPECT_NEAR(areas[2], residential, 0.03 * residential);
  EXPECT_NEAR(areas[0], footway, 0.05 * footway);
  EXPECT_NEAR(areas[1], zone, 0.05 * zone);
}

TEST(OsmReader, CellsOnlyOnTheStreets) {
  const std::string path = write_temp("cells.osm", sample_osm());
  ReadOptions read;
  read.default_height = 10;
  const City city = read_city({path}, read);
  fs::remove(path);
  ViewCellOptions everywhere, streets;
  streets.placement = ViewCellOptions::Placement::Streets;
  const ViewCellMesh all = build_view_cells(city, everywhere);
  const ViewCellMesh on_streets = build_view_cells(city, streets);
  ASSERT_GT(on_streets.cells.size(), 0u);
  EXPECT_LT(on_streets.cells.size(), all.cells.size() / 2);
  double cell_area = 0, street_area = 0;
  const std::vector<Polygon> region = street_region(city.streets);
  for (const ViewCell& c : on_streets.cells) {
    const Vec2 centre = (c.corner[0] + c.corner[1] + c.corner[2]) / 3.0;
    EXPECT_TRUE(std::any_of(region.begin(), region.end(),
                            [&](const Polygon& p) { return inside(p, centre); }))
        << "a cell off the streets at " << centre.x << ", " << centre.y;
    cell_area += std::abs(cross(c.corner[1] - c.corner[0], c.corner[2] - c.corner[0])) / 2;
  }
  for (const Polygon& p : region) street_area += area(p);
  EXPECT_LE(cell_area, street_area * (1 + 1e-6));
  EXPECT_GT(cell_area, 0.8 * street_area);  // the sample's streets pass no building

  // Streets and a region exclude each other; an input without streets cannot have street cells.
  ViewCellOptions both = streets;
  both.region.push_back(Polygon{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {}});
  EXPECT_THROW(build_view_cells(city, both), std::invalid_argument);
  City no_streets = city;
  no_streets.streets = {};
  try {
    build_view_cells(no_streets, streets);
    FAIL() << "street cells without streets";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the input maps no streets"), std::string::npos)
        << e.what();
  }
}

TEST(OsmReader, NotOsmDataIsRefusedNamingTheFile) {
  const std::string path = write_temp("garbage.osm.pbf", "this is no protocol buffer");
  try {
    read_city({path});
    FAIL() << "garbage accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::BadStructure);
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find("not a readable OpenStreetMap file"), std::string::npos)
        << e.what();
  }
  fs::remove(path);
  try {
    read_city({(fs::temp_directory_path() / "urbanpvs_osm_absent.osm.pbf").string()});
    FAIL() << "absent file accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::Unreadable);
  }
}

// "way/123" (the GeoJSON export's @type/@id) is "w123" in the OSM reader.
std::string osm_style(const std::string& geojson_id) {
  for (const auto& [long_name, letter] : {std::pair{"way/", "w"}, std::pair{"relation/", "r"}})
    if (geojson_id.rfind(long_name, 0) == 0)
      return letter + geojson_id.substr(std::string(long_name).size());
  return geojson_id;
}

TEST(OsmReader, HelsinkiPbfGivesTheBuildingsOfItsGeoJsonExport) {
  REQUIRE_SHARED_CITY(pbf, "Helsinki.osm.pbf");
  REQUIRE_SHARED_CITY(geojson, "helsinki_buildings.geojson");
  ReadOptions options;
  options.default_height = 10;
  const City from_osm = read_city({pbf}, options);
  const City from_geojson = read_city({geojson}, options);
  // The export left out the buildings that the extract's edge cuts; the PBF keeps them, as
  // objects that occlude nothing over their nodes in the extract.
  std::set<std::string> exported;
  for (const CityObject& g : from_geojson.objects) exported.insert(osm_style(g.source_id));
  std::size_t cut = 0;
  for (const CityObject& o : from_osm.objects) {
    if (exported.count(o.source_id)) continue;
    ++cut;
    EXPECT_FALSE(o.occludes) << o.source_id;
    EXPECT_TRUE(mentions(from_osm.report.non_occluding, o.source_id + ": ", "outside the extract"))
        << o.source_id;
  }
  EXPECT_EQ(from_osm.objects.size(), from_geojson.objects.size() + cut);
  EXPECT_GT(cut, 40u);
  // The cut buildings move the frame's origin by metres: a shift between the two frames (their
  // tangent planes turn by 1e-6 rad, 1 mm over the extract).
  ASSERT_EQ(from_osm.frame.kind, from_geojson.frame.kind);
  const Vec3 origin =
      LocalFrameMapping(from_osm.frame)
          .to_local(from_geojson.frame.origin_lon, from_geojson.frame.origin_lat, 0);
  const Vec2 shift{origin[0], origin[1]};
  ASSERT_LT(std::hypot(shift.x, shift.y), 20.0);
  std::map<std::string, const CityObject*> by_id;
  for (const CityObject& o : from_osm.objects) by_id[o.source_id] = &o;
  std::size_t compared_vertices = 0;
  for (const CityObject& g : from_geojson.objects) {
    const auto it = by_id.find(osm_style(g.source_id));
    ASSERT_NE(it, by_id.end()) << g.source_id << " missing from the PBF";
    const CityObject& o = *it->second;
    EXPECT_EQ(o.occludes, g.occludes) << g.source_id;
    EXPECT_NEAR(o.bbox.zmax, g.bbox.zmax, 1e-6) << g.source_id;
    EXPECT_NEAR(o.bbox.zmin, g.bbox.zmin, 1e-6) << g.source_id;
    EXPECT_EQ(o.occluders.size(), g.occluders.size()) << g.source_id;
    ASSERT_EQ(o.footprint.size(), g.footprint.size()) << g.source_id;
    for (std::size_t p = 0; p < g.footprint.size(); ++p) {
      ASSERT_EQ(o.footprint[p].outer.size(), g.footprint[p].outer.size()) << g.source_id;
      ASSERT_EQ(o.footprint[p].holes.size(), g.footprint[p].holes.size()) << g.source_id;
      for (std::size_t k = 0; k < g.footprint[p].outer.size(); ++k, ++compared_vertices) {
        const Vec2 d = o.footprint[p].outer[k] - (g.footprint[p].outer[k] + shift);
        EXPECT_LE(std::hypot(d.x, d.y), 0.01) << g.source_id << " vertex " << k;
      }
    }
  }
  EXPECT_GT(compared_vertices, 3000u);
}

TEST(OsmReader, EveryOsmExtractLoadsWithTheDefaults) {
  std::size_t files = 0;
  if (!fs::is_directory(kSharedCities)) GTEST_SKIP() << kSharedCities << " is absent";
  for (const auto& entry : fs::directory_iterator(kSharedCities)) {
    const std::string name = entry.path().filename().string();
    if (name.size() < 8 || name.substr(name.size() - 8) != ".osm.pbf") continue;
    ++files;
    const City city = read_city({entry.path().string()});
    EXPECT_GT(city.objects.size(), 200u) << name;
    for (const CityObject& o : city.objects) {
      ASSERT_TRUE(o.source_id[0] == 'w' || o.source_id[0] == 'r') << name << ": " << o.source_id;
      ASSERT_GT(o.bbox.zmax, o.bbox.zmin) << name << ": " << o.source_id;
    }
  }
  EXPECT_GE(files, 1u);
}

}  // namespace
