// SPDX-License-Identifier: GPL-3.0-or-later
// JSON text sequences: files of one JSON document per line, which large exports and web APIs
// write because a reader can stream them. Two kinds are read, each joined into the one
// document its reader knows:
// - CityJSON text sequences (CityJSONSeq, the `.city.jsonl` files of CityJSON 2.0, the 3D BAG's
//   API, cjio): the first line is a CityJSON object with the transform, the reference system and
//   the metadata but no objects; every further line is a "CityJSONFeature": one city object with
//   its parts, and vertices of its own that its geometries index from 0. The features' vertex
//   indices are moved past the vertices before them, so the CityJSON reader reads a sequence
//   exactly as the same city written as one file.
// - GeoJSON text sequences (RFC 8142, whose records start with the RS character, and the
//   newline-delimited GeoJSON of `ogr2ogr -f GeoJSONSeq` and of large footprint datasets): one
//   Feature per line, joined into a FeatureCollection.
#include <string>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry::detail {
namespace {

// A line without the white space around it, nor RFC 8142's record separator (0x1E).
std::string_view trim(std::string_view s) {
  const auto space = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\x1e';
  };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

// Deepest nesting of boundaries: a MultiSolid's solids, shells, surfaces, rings, indices.
constexpr int kMaxBoundaryDepth = 5;

// Adds `offset` to every vertex index of a geometry's boundaries (nested arrays of them; a
// GeometryInstance's boundaries are its one anchor vertex). Anything else, deeper nesting
// included, is left for the CityJSON reader to refuse with its own message.
void shift_indices(Json& boundaries, std::size_t offset, int depth = 0) {
  if (boundaries.is_array() && depth < kMaxBoundaryDepth) {
    for (Json& b : boundaries) shift_indices(b, offset, depth + 1);
  } else if (boundaries.is_number_unsigned()) {
    boundaries = boundaries.get<std::size_t>() + offset;
  }
}

[[noreturn]] void bad_line(InputProblem problem, const std::string& file, std::size_t line,
                           const std::string& what) {
  throw InputError(problem, file, "line " + std::to_string(line), what);
}

// One CityJSONFeature line into `doc`: its vertices appended, its objects added with their
// indices moved past the vertices already there.
void add_cityjson_feature(Json& doc, Json feature, const std::string& file, std::size_t line) {
  if (!feature.is_object() || !feature.contains("type") || feature["type"] != "CityJSONFeature")
    bad_line(InputProblem::BadStructure, file, line,
             "a CityJSON text sequence holds one \"CityJSONFeature\" per line after the first");
  if (!feature.contains("CityObjects") || !feature["CityObjects"].is_object() ||
      !feature.contains("vertices") || !feature["vertices"].is_array())
    bad_line(InputProblem::BadStructure, file, line,
             "a CityJSONFeature needs a \"CityObjects\" object and a \"vertices\" array");
  Json& vertices = doc["vertices"];
  const std::size_t offset = vertices.size();
  for (Json& v : feature["vertices"]) vertices.push_back(std::move(v));
  Json& objects = doc["CityObjects"];
  for (auto& [id, object] : feature["CityObjects"].items()) {
    if (objects.contains(id))
      bad_line(InputProblem::BadStructure, file, line,
               "city object \"" + id + "\" is also in an earlier line");
    if (object.is_object() && object.contains("geometry") && object["geometry"].is_array())
      for (Json& g : object["geometry"])
        if (g.is_object() && g.contains("boundaries")) shift_indices(g["boundaries"], offset);
    objects[id] = std::move(object);
  }
}

// One GeoJSON Feature line into the FeatureCollection `doc`.
void add_geojson_feature(Json& doc, Json feature, const std::string& file, std::size_t line) {
  if (!feature.is_object() || !feature.contains("type") || feature["type"] != "Feature")
    bad_line(InputProblem::BadStructure, file, line,
             "a GeoJSON text sequence holds one \"Feature\" per line");
  doc["features"].push_back(std::move(feature));
}

bool has_type(const Json& doc, const char* type) {
  return doc.is_object() && doc.contains("type") && doc["type"] == type;
}

}  // namespace

std::optional<Json> join_json_sequence(std::string_view text, const std::string& file) {
  const std::size_t first_end = text.find('\n');
  if (first_end == std::string_view::npos || trim(text.substr(first_end)).empty())
    return std::nullopt;  // one line: a plain JSON document
  // A pretty-printed file's first line is no document of its own: that is the test.
  Json first = Json::parse(trim(text.substr(0, first_end)), nullptr, false);
  Json doc;
  void (*add)(Json&, Json, const std::string&, std::size_t) = nullptr;
  if (has_type(first, "CityJSON")) {
    doc = std::move(first);
    if (!doc.contains("CityObjects") || !doc["CityObjects"].is_object())
      doc["CityObjects"] = Json::object();
    if (!doc.contains("vertices") || !doc["vertices"].is_array()) doc["vertices"] = Json::array();
    add = add_cityjson_feature;
  } else if (has_type(first, "Feature")) {
    doc = {{"type", "FeatureCollection"}, {"features", Json::array()}};
    doc["features"].push_back(std::move(first));
    add = add_geojson_feature;
  } else {
    return std::nullopt;
  }
  std::size_t line = 1;
  for (std::size_t at = first_end + 1; at < text.size();) {
    ++line;
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view content = trim(text.substr(at, end - at));
    at = end + 1;
    if (content.empty()) continue;
    Json item;
    try {
      item = Json::parse(content);
    } catch (const nlohmann::json::exception& e) {
      std::string what = json_error_text(e);
      // The parser counts within the line alone: its "line 1" is the item's line.
      if (auto p = what.find("line 1, column"); p != std::string::npos) what.erase(p, 8);
      bad_line(InputProblem::InvalidJson, file, line, what);
    }
    add(doc, std::move(item), file, line);
  }
  return doc;
}

}  // namespace urbanpvs::geometry::detail
