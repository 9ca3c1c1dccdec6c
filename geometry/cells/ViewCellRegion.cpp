// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/cells/ViewCellRegion.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"

namespace urbanpvs::geometry {
namespace {

using detail::Json;

class RegionReader {
 public:
  RegionReader(const std::string& name, const LocalFrame& frame)
      : name_(name), frame_(frame), mapping_(frame) {}

  void read(const Json& node, const std::string& where, int depth) {
    // GeoJSON nests at most FeatureCollection > Feature > GeometryCollection > geometry; the
    // bound keeps hostile input from exhausting the stack.
    if (depth > 8) throw InputError(InputProblem::BadStructure, name_, where, "nested too deeply");
    if (!node.is_object()) return;
    check_crs(node);
    const std::string type = detail::string_member(node, "type");
    if (type == "FeatureCollection") {
      if (!node.contains("features") || !node["features"].is_array())
        throw InputError(InputProblem::BadStructure, name_, where,
                         "FeatureCollection without \"features\"");
      std::size_t i = 0;
      for (const Json& f : node["features"]) read(f, "#" + std::to_string(i++), depth + 1);
    } else if (type == "Feature") {
      if (node.contains("geometry")) read(node["geometry"], where, depth + 1);
    } else if (type == "GeometryCollection") {
      if (node.contains("geometries") && node["geometries"].is_array())
        for (const Json& g : node["geometries"]) read(g, where, depth + 1);
    } else if (type == "Polygon") {
      polygon(coordinates(node, where), where);
    } else if (type == "MultiPolygon") {
      for (const Json& p : coordinates(node, where)) polygon(p, where);
    }
  }

  std::vector<Polygon> take() {
    if (polygons_.empty())
      throw InputError(InputProblem::EmptyCity, name_, "", "no Polygon or MultiPolygon in region");
    return std::move(polygons_);
  }

 private:
  void check_crs(const Json& node) {
    if (!node.contains("crs") || !node["crs"].is_object()) return;
    const Json& crs = node["crs"];
    std::string named;
    if (crs.contains("properties") && crs["properties"].is_object())
      named = detail::string_member(crs["properties"], "name");
    if (named.empty()) return;
    const std::string c = detail::normalise_crs(named, name_);
    if (!frame_.crs.empty() && c != frame_.crs)
      throw InputError(InputProblem::UnknownCrs, name_, "",
                       "region is in " + c + " but the city is in " + frame_.crs);
  }

  const Json& coordinates(const Json& g, const std::string& where) {
    if (!g.contains("coordinates") || !g["coordinates"].is_array())
      throw InputError(InputProblem::BadStructure, name_, where, "geometry without coordinates");
    return g["coordinates"];
  }

  void polygon(const Json& rings_json, const std::string& where) {
    if (!rings_json.is_array() || rings_json.empty())
      throw InputError(InputProblem::InvalidGeometry, name_, where, "polygon without rings");
    std::vector<Ring> rings;
    for (const Json& ring : rings_json) {
      if (!ring.is_array())
        throw InputError(InputProblem::BadStructure, name_, where, "ring is not an array");
      Ring r;
      for (const Json& p : ring) {
        if (!p.is_array() || p.size() < 2)
          throw InputError(InputProblem::BadStructure, name_, where, "position is not [x, y]");
        const auto local =
            mapping_.to_local(detail::json_number(p[0], name_, where, "coordinate"),
                              detail::json_number(p[1], name_, where, "coordinate"), 0);
        r.push_back({local[0], local[1]});
      }
      rings.push_back(std::move(r));
    }
    ReadReport report;
    for (Polygon& p : clean_polygon(std::move(rings), {name_, where, true}, report))
      polygons_.push_back(std::move(p));
  }

  std::string name_;
  LocalFrame frame_;
  LocalFrameMapping mapping_;
  std::vector<Polygon> polygons_;
};

}  // namespace

std::vector<Polygon> read_region_text(std::string_view text, const std::string& name,
                                      const LocalFrame& frame) {
  Json doc;
  try {
    doc = Json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::exception& e) {
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    throw InputError(InputProblem::InvalidJson, name, "", what);
  }
  if (!doc.is_object() || !doc.contains("type"))
    throw InputError(InputProblem::BadStructure, name, "", "not a GeoJSON object");
  RegionReader reader(name, frame);
  reader.read(doc, "", 0);
  return reader.take();
}

std::vector<Polygon> read_region_file(const std::string& path, const LocalFrame& frame) {
  return read_region_text(detail::read_input_file(path), path, frame);
}

}  // namespace urbanpvs::geometry
