// SPDX-License-Identifier: GPL-3.0-or-later
// CityJSON Text Sequences (CityJSONSeq, the `.city.jsonl` files of CityJSON 2.0 and the 3D BAG's
// API): the first line is a CityJSON object with the transform, the reference system and the
// metadata but no objects; every further line is a "CityJSONFeature": one city object with its
// parts, and vertices of its own that its geometries index from 0. The lines are joined into one
// CityJSON document, each feature's vertex indices moved past the vertices before it, so that
// the CityJSON reader reads a sequence exactly as the same city written as one file.
#include <string>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry::detail {
namespace {

std::string_view trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
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

// One feature line into `doc`: its vertices appended, its objects added with their indices
// moved past the vertices already there.
void add_feature(Json& doc, Json feature, const std::string& file, std::size_t line) {
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

}  // namespace

std::optional<Json> join_cityjson_sequence(std::string_view text, const std::string& file) {
  const std::size_t first_end = text.find('\n');
  if (first_end == std::string_view::npos || trim(text.substr(first_end)).empty())
    return std::nullopt;  // one line: a plain JSON document
  // A pretty-printed file's first line is no document of its own: that is the test.
  Json doc = Json::parse(trim(text.substr(0, first_end)), nullptr, false);
  if (doc.is_discarded() || !doc.is_object() || !doc.contains("type") || doc["type"] != "CityJSON")
    return std::nullopt;
  if (!doc.contains("CityObjects") || !doc["CityObjects"].is_object())
    doc["CityObjects"] = Json::object();
  if (!doc.contains("vertices") || !doc["vertices"].is_array()) doc["vertices"] = Json::array();
  std::size_t line = 1;
  for (std::size_t at = first_end + 1; at < text.size();) {
    ++line;
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view content = trim(text.substr(at, end - at));
    at = end + 1;
    if (content.empty()) continue;
    Json feature;
    try {
      feature = Json::parse(content);
    } catch (const nlohmann::json::exception& e) {
      std::string what = json_error_text(e);
      // The parser counts within the line alone: its "line 1" is the feature's line.
      if (auto p = what.find("line 1, column"); p != std::string::npos) what.erase(p, 8);
      bad_line(InputProblem::InvalidJson, file, line, what);
    }
    add_feature(doc, std::move(feature), file, line);
  }
  return doc;
}

}  // namespace urbanpvs::geometry::detail
