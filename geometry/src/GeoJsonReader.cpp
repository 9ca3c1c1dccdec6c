// SPDX-License-Identifier: GPL-3.0-or-later
// GeoJSON (RFC 7946) reader for building footprints with height attributes, as exported from
// OpenStreetMap or municipal cadastres. Footprints are extruded from the ground (z = 0) to their
// height; OSM building:part features join the building whose outline contains them, as CityJSON
// BuildingParts do, and then alone define its occluders (the outline's own height tag is the
// building's maximum, which would overstate a lower wing).
#include <cmath>
#include <cstdlib>
#include <optional>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/InputError.hpp"
#include "urbanpvs/geometry/RingCleanup.hpp"

namespace urbanpvs::geometry::detail {
namespace {

const Json& features_of(const Json& doc, const std::string& file) {
  static const Json empty = Json::array();
  if (doc["type"] == "Feature") return empty;  // handled by the caller as a single feature
  if (!doc.contains("features") || !doc["features"].is_array())
    throw InputError(InputProblem::BadStructure, file, "", "FeatureCollection without \"features\"");
  return doc["features"];
}

template <class F>
void for_each_feature(const Json& doc, const std::string& file, F&& f) {
  if (doc["type"] == "Feature") {
    f(doc, 0);
    return;
  }
  const Json& fs = features_of(doc, file);
  for (std::size_t i = 0; i < fs.size(); ++i) f(fs[i], i);
}

std::string feature_id(const Json& feature, std::size_t index) {
  auto text = [](const Json& v) -> std::string {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number_integer()) return std::to_string(v.get<long long>());
    if (v.is_number()) return v.dump();
    return {};
  };
  if (feature.contains("id"))
    if (std::string s = text(feature["id"]); !s.empty()) return s;
  if (feature.contains("properties") && feature["properties"].is_object()) {
    const Json& p = feature["properties"];
    if (p.contains("id"))
      if (std::string s = text(p["id"]); !s.empty()) return s;
    // OSM exports (osmium, overpass) name the element as @type/@id: "way/4253124".
    if (p.contains("@id"))
      if (std::string s = text(p["@id"]); !s.empty())
        return p.contains("@type") && p["@type"].is_string()
                   ? p["@type"].get<std::string>() + "/" + s
                   : s;
  }
  return "#" + std::to_string(index);
}

// A geometry's polygons as raw coordinate rings: [[[x, y], ...], [hole], ...].
std::vector<const Json*> polygons_of(const Json& g, const std::string& file,
                                     const std::string& id) {
  const std::string type = string_member(g, "type");
  if (!g.contains("coordinates") || !g["coordinates"].is_array())
    throw InputError(InputProblem::BadStructure, file, id, type + " without \"coordinates\"");
  const Json& c = g["coordinates"];
  std::vector<const Json*> out;
  if (type == "Polygon") {
    out.push_back(&c);
  } else {
    for (const Json& p : c) out.push_back(&p);
  }
  if (out.empty()) throw InputError(InputProblem::InvalidGeometry, file, id, type + " without polygons");
  for (const Json* p : out)
    if (!p->is_array() || p->empty())
      throw InputError(InputProblem::InvalidGeometry, file, id, "polygon without rings");
  return out;
}

bool is_polygonal(const Json& g) {
  const std::string t = g.is_object() ? string_member(g, "type") : "";
  return t == "Polygon" || t == "MultiPolygon";
}

Vec2 position(const Json& p, const std::string& file, const std::string& id) {
  if (!p.is_array() || p.size() < 2)
    throw InputError(InputProblem::BadStructure, file, id, "position is not [x, y]");
  return {json_number(p[0], file, id, "coordinate"), json_number(p[1], file, id, "coordinate")};
}

// "12", "12.5 m", "12,5m", "40 ft", "40'" -> metres; nullopt when it is no length.
std::optional<double> parse_length(const Json& v) {
  if (v.is_number()) {
    const double d = v.get<double>();
    return std::isfinite(d) ? std::optional<double>(d) : std::nullopt;
  }
  if (!v.is_string()) return std::nullopt;
  std::string s = v.get<std::string>();
  for (char& ch : s)
    if (ch == ',') ch = '.';
  const char* begin = s.c_str();
  char* end = nullptr;
  const double d = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(d)) return std::nullopt;
  std::string unit(end);
  unit.erase(0, unit.find_first_not_of(" \t"));
  unit.erase(unit.find_last_not_of(" \t") + 1);
  if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres")
    return d;
  if (unit == "ft" || unit == "'" || unit == "feet") return d * 0.3048;
  return std::nullopt;
}

struct Feature {
  std::string id;
  std::vector<Polygon> polygons;
  Box2 box;
  bool part = false;
  double min_height = 0;
  std::optional<double> height;  // from attributes; the default is applied when needed
  bool height_from_levels = false;
};

struct HeightReader {
  const std::string& file;
  const ReadOptions& options;
  ReadReport& report;

  std::optional<double> length(const Json& props, const char* key, const std::string& id) {
    if (!props.contains(key) || props[key].is_null()) return std::nullopt;
    std::optional<double> v = parse_length(props[key]);
    if (!v)
      report.warnings.push_back(file + ": " + id + ": cannot read " + key + " " +
                                props[key].dump() + "; ignored");
    return v;
  }

  void read(const Json& props, Feature& f) {
    for (const char* key : {"height", "building:height", "measuredHeight"})
      if (!f.height) f.height = length(props, key, f.id);
    if (!f.height)
      if (std::optional<double> levels = length(props, "building:levels", f.id)) {
        f.height = *levels * options.level_height;
        f.height_from_levels = true;
      }
    if (std::optional<double> m = length(props, "min_height", f.id))
      f.min_height = *m;
    else if (std::optional<double> l = length(props, "building:min_level", f.id))
      f.min_height = *l * options.level_height;
  }
};

Feature read_feature(const Json& feature, std::size_t index, const std::string& file,
                     const LocalFrameMapping& mapping, HeightReader& heights, ReadReport& report) {
  Feature f;
  f.id = feature_id(feature, index);
  const Json& g = feature["geometry"];
  for (const Json* poly : polygons_of(g, file, f.id)) {
    std::vector<Ring> rings;
    for (const Json& ring : *poly) {
      if (!ring.is_array())
        throw InputError(InputProblem::BadStructure, file, f.id, "ring is not an array");
      Ring r;
      for (const Json& p : ring) {
        const Vec2 in = position(p, file, f.id);
        const auto local = mapping.to_local(in.x, in.y, 0);
        r.push_back({local[0], local[1]});
      }
      rings.push_back(std::move(r));
    }
    f.polygons.push_back(clean_polygon(std::move(rings), {file, f.id, true}, report));
    f.box.extend(bounds(f.polygons.back()));
  }
  const Json& props = feature.contains("properties") && feature["properties"].is_object()
                          ? feature["properties"]
                          : Json::object();
  f.part = props.contains("building:part") && props["building:part"] != "no";
  heights.read(props, f);
  return f;
}

// A point certainly inside the polygon (for part-in-building tests): the midpoint of the first
// interior chord found by casting a horizontal line through the middle of the outer ring.
Vec2 interior_point(const Polygon& p) {
  const Box2 b = bounds(p.outer);
  for (double t : {0.5, 0.37, 0.63, 0.21, 0.79, 0.1, 0.9}) {
    const double y = b.min.y + t * (b.max.y - b.min.y);
    std::vector<double> xs;
    for_each_edge(p, [&](Vec2 a, Vec2 c) {
      if ((a.y > y) != (c.y > y)) xs.push_back(a.x + (y - a.y) * (c.x - a.x) / (c.y - a.y));
    });
    std::sort(xs.begin(), xs.end());
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
      if (xs[i + 1] > xs[i]) return {0.5 * (xs[i] + xs[i + 1]), y};
  }
  return p.outer.front();
}

double feature_height(Feature& f, const std::string& file, const ReadOptions& options,
                      ReadReport& report) {
  if (f.height) {
    if (f.height_from_levels) ++report.level_heights;
    return *f.height;
  }
  if (!options.default_height)
    throw InputError(InputProblem::MissingHeight, file, f.id,
                     "no height, building:height, measuredHeight or building:levels "
                     "(give a default height)");
  ++report.default_heights;
  f.height = *options.default_height;
  return *f.height;
}

void add_occluders(Feature& f, CityObject& o, const std::string& file, const ReadOptions& options,
                   ReadReport& report) {
  const double h = feature_height(f, file, options, report);
  for (const Polygon& p : f.polygons) o.bbox.extend(bounds(p).min, f.min_height),
      o.bbox.extend(bounds(p).max, h);
  // Parts that do not reach the ground (min_height > 0) leave open space below them; in 2.5D
  // they cannot occlude anything conservatively.
  if (f.min_height > 0 || h <= 0) return;
  for (const Polygon& p : f.polygons) o.occluders.push_back({p, 0.0, h});
}

}  // namespace

InputScan scan_geojson(const Json& doc, const std::string& file, const ReadOptions& options) {
  InputScan scan;
  std::string declared;
  if (doc.contains("crs") && doc["crs"].is_object()) {
    const Json& c = doc["crs"];
    if (!c.contains("properties") || !c["properties"].is_object() ||
        !c["properties"].contains("name") || !c["properties"]["name"].is_string())
      throw InputError(InputProblem::UnknownCrs, file, "crs", "no properties.name");
    declared = normalise_crs(c["properties"]["name"].get<std::string>(), file);
  }
  for_each_feature(doc, file, [&](const Json& f, std::size_t i) {
    if (!f.is_object() || !f.contains("geometry") || !is_polygonal(f["geometry"])) return;
    const std::string id = feature_id(f, i);
    for (const Json* poly : polygons_of(f["geometry"], file, id))
      for (const Json& ring : *poly)
        if (ring.is_array())
          for (const Json& p : ring) scan.bounds.extend(position(p, file, id));
  });
  const bool lonlat_range = !scan.bounds.empty() && scan.bounds.min.x >= -180 &&
                            scan.bounds.max.x <= 180 && scan.bounds.min.y >= -90 &&
                            scan.bounds.max.y <= 90;
  using C = ReadOptions::Coordinates;
  if (options.coordinates == C::Geographic) {
    scan.kind = LocalFrame::Kind::Geographic;
    scan.note = file + ": WGS84 lon/lat (as requested)";
  } else if (options.coordinates == C::Projected) {
    scan.kind = LocalFrame::Kind::Projected;
    scan.note = file + ": projected metres (as requested)";
  } else if (!declared.empty()) {
    scan.kind = is_geographic_crs(declared) ? LocalFrame::Kind::Geographic
                                            : LocalFrame::Kind::Projected;
    scan.note = file + ": reference system " + declared + " from the \"crs\" member";
  } else {
    scan.kind = lonlat_range ? LocalFrame::Kind::Geographic : LocalFrame::Kind::Projected;
    scan.note = file + (lonlat_range
                            ? ": no \"crs\"; coordinates lie within lon/lat range, read as WGS84"
                            : ": no \"crs\"; coordinates exceed lon/lat range, read as projected "
                              "metres");
  }
  if (scan.kind == LocalFrame::Kind::Geographic && !lonlat_range && !scan.bounds.empty())
    throw InputError(InputProblem::UnknownCrs, file, "",
                     "coordinates are read as WGS84 lon/lat but exceed its range");
  scan.crs = declared.empty() && scan.kind == LocalFrame::Kind::Geographic ? "OGC:CRS84"
                                                                            : declared;
  return scan;
}

void load_geojson(const Json& doc, const std::string& file, const LocalFrameMapping& mapping,
                  const ReadOptions& options, City& city) {
  ReadReport& report = city.report;
  HeightReader heights{file, options, report};
  std::vector<Feature> buildings, parts;
  for_each_feature(doc, file, [&](const Json& feature, std::size_t i) {
    if (!feature.is_object() || string_member(feature, "type") != "Feature")
      throw InputError(InputProblem::BadStructure, file, "#" + std::to_string(i),
                       "not a GeoJSON Feature");
    if (!feature.contains("geometry") || feature["geometry"].is_null()) {
      ++report.ignored_types["(feature without geometry)"];
      return;
    }
    const Json& geometry = feature["geometry"];
    if (!geometry.is_object() || !geometry.contains("type") || !geometry["type"].is_string())
      throw InputError(InputProblem::BadStructure, file, feature_id(feature, i),
                       "geometry has no \"type\" string");
    if (!is_polygonal(geometry)) {
      const Json& g = feature["geometry"];
      const std::string type = string_member(g, "type");
      ++report.ignored_types[type.empty() ? "(untyped geometry)" : type];
      return;
    }
    try {
      Feature f = read_feature(feature, i, file, mapping, heights, report);
      (f.part ? parts : buildings).push_back(std::move(f));
    } catch (const InputError& e) {
      if (!options.skip_invalid || e.problem() != InputProblem::InvalidGeometry) throw;
      ++report.skipped_invalid;
      report.warnings.push_back(std::string(e.what()) + " (skipped)");
    }
  });

  // Attach each part to the smallest building outline that contains it.
  std::vector<std::vector<Feature*>> parts_of(buildings.size());
  std::vector<Feature*> orphans;
  for (Feature& p : parts) {
    const Vec2 q = interior_point(p.polygons.front());
    std::size_t best = buildings.size();
    double best_area = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < buildings.size(); ++b) {
      if (!buildings[b].box.overlaps(p.box)) continue;
      for (const Polygon& poly : buildings[b].polygons)
        if (inside(poly, q) && area(poly) < best_area) best = b, best_area = area(poly);
    }
    (best < buildings.size() ? parts_of[best].push_back(&p) : orphans.push_back(&p));
  }

  auto object_of = [&](Feature& f) {
    CityObject o;
    o.source_id = f.id;
    o.footprint = f.polygons;
    o.ground_z = 0;
    return o;
  };
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    Feature& f = buildings[b];
    CityObject o = object_of(f);
    if (parts_of[b].empty()) {
      add_occluders(f, o, file, options, report);
    } else {
      for (Feature* p : parts_of[b]) add_occluders(*p, o, file, options, report);
      // The outline still bounds the object; its height only matters when it has its own.
      const double h = f.height.value_or(o.bbox.zmax);
      for (const Polygon& poly : f.polygons) o.bbox.extend(bounds(poly).min, 0.0),
          o.bbox.extend(bounds(poly).max, h);
    }
    city.objects.push_back(std::move(o));
  }
  for (Feature* p : orphans) {
    CityObject o = object_of(*p);
    add_occluders(*p, o, file, options, report);
    city.objects.push_back(std::move(o));
  }
}

}  // namespace urbanpvs::geometry::detail
