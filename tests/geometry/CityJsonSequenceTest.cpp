// SPDX-License-Identifier: GPL-3.0-or-later
// CityJSON text sequences (.city.jsonl): a city written by this test as a sequence (a header line,
// then one CityJSONFeature per building with its parts and its own vertices, indexed from 0)
// reads exactly as the same city written as one CityJSON file: the bundled district and, where
// ../shared/cities has it, the 3D BAG tile. The sequence's own faults name their line
// (tests/data/bad/cityjsonseq_*, ReaderTest.cpp).
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

#include "SharedCities.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace {

using namespace urbanpvs::geometry;
using Json = nlohmann::ordered_json;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

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

// What the reader made of an object, every coordinate to the last bit.
std::string digest(const CityObject& o) {
  std::string s;
  char b[64];
  const auto number = [&](double v) {
    std::snprintf(b, sizeof b, "%.17g ", v);
    s += b;
  };
  const auto polygon = [&](const Polygon& p) {
    for (const Vec2& v : p.outer) number(v.x), number(v.y);
    for (const Ring& h : p.holes) {
      s += "| ";
      for (const Vec2& v : h) number(v.x), number(v.y);
    }
    s += "; ";
  };
  s += o.occludes ? "occludes " : "occludes nothing ";
  for (double v : {o.bbox.xy.min.x, o.bbox.xy.min.y, o.bbox.zmin, o.bbox.xy.max.x, o.bbox.xy.max.y,
                   o.bbox.zmax, o.ground_z})
    number(v);
  for (const Polygon& p : o.footprint) polygon(p);
  for (const OccluderPrism& prism : o.occluders) {
    polygon(prism.footprint);
    number(prism.ground_z), number(prism.top_z);
  }
  s += std::to_string(o.surfaces.size()) + " surfaces";
  return s;
}

void expect_same_city(const City& file, const City& sequence) {
  ASSERT_EQ(file.objects.size(), sequence.objects.size());
  std::map<std::string, std::string> by_id;
  for (const CityObject& o : file.objects) by_id[o.source_id] = digest(o);
  for (const CityObject& o : sequence.objects) {
    ASSERT_TRUE(by_id.count(o.source_id)) << o.source_id;
    EXPECT_EQ(by_id[o.source_id], digest(o)) << o.source_id;
  }
  EXPECT_EQ(file.frame.crs, sequence.frame.crs);
  EXPECT_EQ(file.report.repaired_orientation, sequence.report.repaired_orientation);
  EXPECT_EQ(file.report.repaired_duplicate_points, sequence.report.repaired_duplicate_points);
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
