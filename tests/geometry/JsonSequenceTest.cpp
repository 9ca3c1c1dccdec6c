// SPDX-License-Identifier: GPL-3.0-or-later
// JSON text sequences (JsonSequence.cpp). A city written by this test as a CityJSON text
// sequence (a header line, then one CityJSONFeature per building with its parts and its own
// vertices, indexed from 0) reads exactly as the same city written as one CityJSON file: the
// bundled district and, where ../shared/cities has it, the 3D BAG tile. GeoJSON written one
// Feature per line, with or without RFC 8142's record separators, reads exactly as the
// FeatureCollection: footprints written by the test and, where ../shared/cities has them,
// Helsinki's. The sequences' own faults
// name their line (tests/data/bad/*seq_*, ReaderTest.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
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

// The vertex indices of `boundaries` renumbered from 0 in order of first use, the used
// vertices appended to `vertices` in that order.
void renumber(Json& boundaries, const Json& all, std::map<std::size_t, std::size_t>& index,
              Json& vertices) {
  if (boundaries.is_array()) {
    for (Json& b : boundaries) renumber(b, all, index, vertices);
    return;
  }
  const auto old = boundaries.get<std::size_t>();
  auto [it, added] = index.try_emplace(old, vertices.size());
  if (added) vertices.push_back(all[old]);
  boundaries = it->second;
}

// `doc` as a CityJSON text sequence: every object without parents becomes a feature with its
// descendants, written the way the 3D BAG's API writes them.
std::string as_sequence(const Json& doc) {
  Json header = doc;
  header["CityObjects"] = Json::object();
  header["vertices"] = Json::array();
  std::string out = header.dump() + "\n";
  const Json& objects = doc["CityObjects"];
  std::set<std::string> written;
  for (const auto& [id, object] : objects.items()) {
    if (object.contains("parents") && !object["parents"].empty()) continue;
    Json feature = {{"type", "CityJSONFeature"},
                    {"id", id},
                    {"CityObjects", Json::object()},
                    {"vertices", Json::array()}};
    std::map<std::size_t, std::size_t> index;
    std::vector<std::string> family{id};
    for (std::size_t k = 0; k < family.size(); ++k) {
      const Json& member = objects[family[k]];
      if (member.contains("children"))
        for (const Json& c : member["children"]) family.push_back(c.get<std::string>());
    }
    for (const std::string& m : family) {
      if (!written.insert(m).second) continue;
      Json member = objects[m];
      if (member.contains("geometry"))
        for (Json& g : member["geometry"])
          renumber(g["boundaries"], doc["vertices"], index, feature["vertices"]);
      feature["CityObjects"][m] = std::move(member);
    }
    out += feature.dump() + "\n";
  }
  EXPECT_EQ(written.size(), objects.size()) << "every object belongs to a family";
  return out;
}

void check_sequence_of(const std::string& path) {
  const std::string text = read_text(path);
  const Json doc = Json::parse(text);
  const std::string lines = as_sequence(doc);
  ASSERT_GT(std::count(lines.begin(), lines.end(), '\n'), 2);
  const City file = read_city_text(text, "city.city.json", {});
  const City sequence = read_city_text(lines, "city.city.jsonl", {});
  expect_same_city(file, sequence);
}

TEST(CityJsonSequence, BundledDistrictReadsAsItsFile) {
  check_sequence_of(std::string(URBANPVS_SOURCE_DIR) + "/cities/sample/district.city.json");
}

TEST(CityJsonSequence, TuDelft3dBagTileReadsAsItsFile) {
  REQUIRE_SHARED_CITY(path, "tudelft_3dbag_tile5910.city.json");
  check_sequence_of(path);
}

// `doc`'s features one per line, each after `prefix` (RFC 8142: the record separator).
std::string as_geojson_sequence(const Json& doc, const std::string& prefix) {
  std::string out;
  for (const Json& f : doc["features"]) out += prefix + f.dump() + "\n";
  return out;
}

// Footprints in lon/lat as a footprint dataset writes them, one with an unknown height (-1):
// it stays an object that occludes nothing, as tall as a building may be (GeoJsonReader.cpp).
Json footprints() {
  Json doc = {{"type", "FeatureCollection"}, {"features", Json::array()}};
  for (int i = 0; i < 8; ++i) {
    const double x = 4.37 + 0.0004 * i, y = 52.0 + 0.0001 * (i % 3);
    Json ring = Json::array();
    for (auto [dx, dy] : {std::pair{0.0, 0.0}, {0.0002, 0.0}, {0.0002, 0.0002}, {0.0, 0.0002}})
      ring.push_back({x + dx, y + dy});
    ring.push_back(ring[0]);
    doc["features"].push_back({{"type", "Feature"},
                               {"properties", {{"height", i == 5 ? -1.0 : 6.0 + i}}},
                               {"geometry", {{"type", "Polygon"}, {"coordinates", {ring}}}}});
  }
  return doc;
}

TEST(GeoJsonSequence, FootprintsReadAsTheirFeatureCollection) {
  const Json doc = footprints();
  const City file = read_city_text(doc.dump(), "city.geojson", {});
  for (const std::string prefix : {"", "\x1e"}) {
    const City sequence = read_city_text(as_geojson_sequence(doc, prefix), "city.geojsonl", {});
    expect_same_city(file, sequence);
  }
  ASSERT_EQ(file.objects.size(), 8u);
  EXPECT_TRUE(file.objects[4].occludes);
  EXPECT_DOUBLE_EQ(file.objects[4].bbox.zmax, 10.0);
  // -1 is "unknown": no occluder, and tested as tall as a building may be.
  EXPECT_FALSE(file.objects[5].occludes);
  EXPECT_TRUE(file.objects[5].occluders.empty());
  EXPECT_DOUBLE_EQ(file.objects[5].bbox.zmax, ReadOptions{}.max_height);
  ASSERT_EQ(file.report.non_occluding.size(), 1u);
  EXPECT_NE(file.report.non_occluding[0].find("height -1.0 is no height"), std::string::npos)
      << file.report.non_occluding[0];
  // With a default height, that height stands in for it.
  ReadOptions with_default;
  with_default.default_height = 9;
  const City defaulted = read_city_text(doc.dump(), "city.geojson", with_default);
  EXPECT_TRUE(defaulted.objects[5].occludes);
  EXPECT_DOUBLE_EQ(defaulted.objects[5].bbox.zmax, 9.0);
  EXPECT_EQ(defaulted.report.default_heights, 1u);
}

TEST(GeoJsonSequence, HelsinkiReadsAsItsFeatureCollection) {
  REQUIRE_SHARED_CITY(path, "helsinki_buildings.geojson");
  ReadOptions options;
  options.default_height = 12;  // most of its buildings have no height tag
  const std::string text = read_text(path);
  const Json doc = Json::parse(text);
  const City file = read_city_text(text, "city.geojson", options);
  expect_same_city(file, read_city_text(as_geojson_sequence(doc, ""), "city.geojsonl", options));
}

TEST(CityJsonSequence, BlankLinesAndCarriageReturnsAreAllowed) {
  const std::string header =
      R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.01,0.01,0.01],)"
      R"("translate":[0,0,0]},"CityObjects":{},"vertices":[]})";
  const std::string feature =
      R"({"type":"CityJSONFeature","id":"B","CityObjects":{"B":{"type":"Building",)"
      R"("geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[[0,3,2,1]],[[4,5,6,7]],)"
      R"([[0,1,5,4]],[[1,2,6,5]],[[2,3,7,6]],[[3,0,4,7]]]}]}},"vertices":[[0,0,0],[1000,0,0],)"
      R"([1000,1000,0],[0,1000,0],[0,0,1200],[1000,0,1200],[1000,1000,1200],[0,1000,1200]]})";
  std::string second = feature;
  for (std::size_t at; (at = second.find("\"B\"")) != std::string::npos;)
    second.replace(at, 3, "\"C\"");
  const City city =
      read_city_text(header + "\r\n\r\n" + feature + "\r\n" + second, "two.city.jsonl", {});
  ASSERT_EQ(city.objects.size(), 2u);
  EXPECT_EQ(city.objects[0].source_id, "B");
  EXPECT_EQ(city.objects[1].source_id, "C");
  EXPECT_DOUBLE_EQ(city.objects[1].bbox.zmax - city.objects[1].bbox.zmin, 12.0);
}

}  // namespace
