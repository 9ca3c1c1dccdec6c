// SPDX-License-Identifier: GPL-3.0-or-later
// ReadOptions::payload_key: each object of the bundled district carries the named CityJSON
// attribute or GeoJSON property, checked against the files read independently with
// nlohmann::json: strings as given, other values as their compact JSON text, nothing when
// absent, and a warning when no object has the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/ReadSettings.hpp"

namespace {

namespace fs = std::filesystem;
using namespace urbanpvs::geometry;
using Json = nlohmann::json;

const fs::path kSample = fs::path(URBANPVS_SOURCE_DIR) / "cities" / "sample";

Json read_json(const fs::path& path) {
  std::ifstream in(path);
  return Json::parse(in);
}

/// The value the reader must give: the string itself, or the JSON text of anything else.
std::string expected_payload(const Json& attributes, const std::string& key) {
  if (!attributes.is_object() || !attributes.contains(key) || attributes[key].is_null()) return {};
  const Json& v = attributes[key];
  return v.is_string() ? v.get<std::string>() : v.dump();
}

std::map<std::string, std::string> payloads(const City& city) {
  std::map<std::string, std::string> out;
  for (const CityObject& o : city.objects) out[o.source_id] = o.payload;
  return out;
}

TEST(Payload, CityJsonAttributeOfEachBuilding) {
  const fs::path path = kSample / "district.city.json";
  const Json doc = read_json(path);
  for (const std::string key : {"block", "measuredHeight"}) {
    ReadOptions options;
    options.payload_key = key;
    const City city = read_city({path.string()}, options);
    EXPECT_EQ(city.payload_key, key);
    const auto got = payloads(city);
    std::size_t checked = 0;
    for (const auto& [id, obj] : doc["CityObjects"].items()) {
      if (obj["type"] != "Building") continue;
      ASSERT_TRUE(got.count(id)) << id;
      const std::string want = expected_payload(obj.value("attributes", Json::object()), key);
      EXPECT_EQ(got.at(id), want) << id;
      checked += want.empty() ? 0 : 1;
    }
    EXPECT_GT(checked, 300u) << key;  // the district's buildings all have both attributes
  }
}

TEST(Payload, GeoJsonPropertyOfEachBuilding) {
  const fs::path path = kSample / "district.geojson";
  const Json doc = read_json(path);
  ReadOptions options;
  options.payload_key = "block";
  const auto got = payloads(read_city({path.string()}, options));
  std::size_t checked = 0;
  for (const Json& f : doc["features"]) {
    const std::string id = f["id"].get<std::string>();
    if (!got.count(id)) continue;  // a building:part joins its building
    EXPECT_EQ(got.at(id), expected_payload(f["properties"], "block")) << id;
    ++checked;
  }
  EXPECT_GT(checked, 300u);
}

TEST(Payload, NoneWithoutAKeyAndAWarningForAKeyNobodyHas) {
  const std::string path = (kSample / "district.geojson").string();
  for (const CityObject& o : read_city({path}).objects) EXPECT_EQ(o.payload, "");
  ReadOptions options;
  options.payload_key = "nosuch";
  const City city = read_city({path}, options);
  for (const CityObject& o : city.objects) EXPECT_EQ(o.payload, "");
  ASSERT_FALSE(city.report.warnings.empty());
  EXPECT_EQ(city.report.warnings.back(),
            "--payload nosuch: no object has this attribute, property or tag");
}

TEST(Payload, ValuesOfEveryJsonType) {
  const std::string text = R"({"type": "FeatureCollection",
    "crs": {"type": "name", "properties": {"name": "EPSG:3067"}}, "features": [
    {"type": "Feature", "id": "s", "properties": {"height": 9, "k": "tiles/\u00e9"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]]]}},
    {"type": "Feature", "id": "n", "properties": {"height": 9, "k": 4.5},
     "geometry": {"type": "Polygon", "coordinates": [[[20, 0], [30, 0], [30, 10], [20, 10], [20, 0]]]}},
    {"type": "Feature", "id": "b", "properties": {"height": 9, "k": true},
     "geometry": {"type": "Polygon", "coordinates": [[[40, 0], [50, 0], [50, 10], [40, 10], [40, 0]]]}},
    {"type": "Feature", "id": "o", "properties": {"height": 9, "k": {"lod": [1, 2]}},
     "geometry": {"type": "Polygon", "coordinates": [[[60, 0], [70, 0], [70, 10], [60, 10], [60, 0]]]}},
    {"type": "Feature", "id": "z", "properties": {"height": 9, "k": null},
     "geometry": {"type": "Polygon", "coordinates": [[[80, 0], [90, 0], [90, 10], [80, 10], [80, 0]]]}}
  ]})";
  ReadOptions options;
  options.payload_key = "k";
  const auto got = payloads(read_city_text(text, "types.geojson", options));
  EXPECT_EQ(got.at("s"), "tiles/\xC3\xA9");
  EXPECT_EQ(got.at("n"), "4.5");
  EXPECT_EQ(got.at("b"), "true");
  EXPECT_EQ(got.at("o"), R"({"lod":[1,2]})");
  EXPECT_EQ(got.at("z"), "");
}

TEST(Payload, InvalidUtf8InATagBecomesReplacementCharacters) {
  // OSM PBF tag values reach the reader unchecked (JSON files are checked by the parser).
  urbanpvs::geometry::detail::Json tags = {{"ref", "a\xFFz"}, {"n", 3}};
  EXPECT_EQ(urbanpvs::geometry::detail::payload_of(tags, "ref"), "a\xEF\xBF\xBDz");
  EXPECT_EQ(urbanpvs::geometry::detail::payload_of(tags, "n"), "3");
  EXPECT_EQ(urbanpvs::geometry::detail::payload_of(tags, ""), "");
}

TEST(Payload, TheKeyMustBeUtf8) {
  const Setting<ReadOptions>* s = find_setting(read_settings(), "payload");
  ASSERT_NE(s, nullptr);
  ReadOptions options;
  s->set(options, "ref:tile");
  EXPECT_EQ(options.payload_key, "ref:tile");
  s->set(options, "none");
  EXPECT_EQ(options.payload_key, "");
  try {
    s->set(options, "bad\xFF");
    FAIL() << "a name that is not UTF-8 was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--payload expects a name in UTF-8, got \"bad\xFF\"");
  }
}

}  // namespace
