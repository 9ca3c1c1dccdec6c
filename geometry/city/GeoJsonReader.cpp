// SPDX-License-Identifier: GPL-3.0-or-later
// GeoJSON (RFC 7946) reader for building footprints with height attributes, as exported from
// OpenStreetMap or municipal cadastres. Footprints are extruded from the ground (z = 0, or the
// terrain of a CityJSON file read with them: CityReader.cpp) to their height; OSM building:part
// features join the building whose outline contains them, as CityJSON BuildingParts do, and then
// alone define its occluders (the outline's own height tag is the building's maximum, which
// would overstate a lower wing).
//
// Thesis 7.1: an occluder must lie inside the real building. OSM's `height` is the top of the
// roof, so a pitched roof's occluder ends at the eaves (height - roof:height), with the faces
// of the roof above them where roof:shape names one RoofShapes.hpp models, and a part that
// starts above the ground (min_height, building:min_level) gives no occluder at all: the 2.5D
// occluders downstream stand on the ground, and the space below such a part is open.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/ObjectOutline.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/city/RoofPrisms.hpp"
#include "urbanpvs/geometry/city/RoofShapes.hpp"

namespace urbanpvs::geometry::detail {
namespace {

const Json& features_of(const Json& doc, const std::string& file) {
  static const Json empty = Json::array();
  if (doc["type"] == "Feature") return empty;  // handled by the caller as a single feature
  if (!doc.contains("features") || !doc["features"].is_array())
    throw InputError(InputProblem::BadStructure, file, "",
                     "FeatureCollection without \"features\"");
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

// The polygons of a Polygon, a MultiPolygon or a GeometryCollection (its polygonal members, at
// any depth: exports of OSM relations write them so), each as given: an array of rings, maybe
// empty. Throws BadStructure for coordinates that are no array.
void polygon_arrays(const Json& g, const std::string& file, const std::string& id,
                    std::vector<const Json*>& out) {
  const std::string type = string_member(g, "type");
  if (type == "GeometryCollection") {
    if (g.contains("geometries") && g["geometries"].is_array())
      for (const Json& member : g["geometries"])
        if (member.is_object()) polygon_arrays(member, file, id, out);
    return;
  }
  if (type != "Polygon" && type != "MultiPolygon") return;
  if (!g.contains("coordinates") || !g["coordinates"].is_array())
    throw InputError(InputProblem::BadStructure, file, id, type + " without \"coordinates\"");
  const Json& c = g["coordinates"];
  if (type == "Polygon") {
    out.push_back(&c);
  } else {
    for (const Json& p : c) out.push_back(&p);
  }
}

std::vector<const Json*> polygon_arrays(const Json& g, const std::string& file,
                                        const std::string& id) {
  std::vector<const Json*> out;
  polygon_arrays(g, file, id, out);
  return out;
}

// The polygons with rings, for reading them: an empty one (a MultiPolygon's `[]` member, as
// some exports write) has no area to lose and is left out, said in a warning; --strict, or
// none left, refuses the feature (InvalidGeometry: without --strict it is kept over its box).
std::vector<const Json*> polygons_of(const Json& g, const std::string& file, const std::string& id,
                                     bool strict, ReadReport& report) {
  const std::string type = string_member(g, "type");
  std::vector<const Json*> out;
  std::size_t empty = 0;
  for (const Json* p : polygon_arrays(g, file, id)) {
    if (p->is_array() && !p->empty())
      out.push_back(p);
    else
      ++empty;
  }
  if (empty > 0 && (strict || out.empty()))
    throw InputError(InputProblem::InvalidGeometry, file, id, "polygon without rings");
  if (out.empty())
    throw InputError(InputProblem::InvalidGeometry, file, id, type + " without polygons");
  if (empty > 0)
    report.warnings.push_back(file + ": " + id + ": " + std::to_string(empty) +
                              " polygon(s) without rings left out");
  return out;
}

bool is_polygonal(const Json& g) {
  if (!g.is_object()) return false;
  const std::string t = string_member(g, "type");
  if (t == "GeometryCollection")
    return g.contains("geometries") && g["geometries"].is_array() &&
           std::any_of(g["geometries"].begin(), g["geometries"].end(),
                       [](const Json& m) { return is_polygonal(m); });
  return t == "Polygon" || t == "MultiPolygon";
}

Vec2 position(const Json& p, const std::string& file, const std::string& id) {
  if (!p.is_array() || p.size() < 2)
    throw InputError(InputProblem::BadStructure, file, id, "position is not [x, y]");
  return {json_number(p[0], file, id, "coordinate"), json_number(p[1], file, id, "coordinate")};
}

struct Feature {
  std::string id;
  std::vector<Polygon> polygons;
  Box2 box;
  bool part = false;
  double min_height = 0;
  /// min_height or building:min_level is given but unreadable: where the part starts is
  /// unknown, so it may float (no occluder).
  bool base_unknown = false;
  std::optional<double> height;  // from attributes; the default is applied when needed
  bool height_from_levels = false;
  std::optional<double> levels_height;   // building:levels x level height
  std::string roof_shape;                // lower case; "" when not given
  std::optional<double> roof_direction;  // roof:direction, degrees clockwise from north
  RidgeOrientation roof_ridge = RidgeOrientation::Unknown;  // roof:orientation
  bool roof_height_in_metres = false;  // roof:height given, not guessed from roof:levels
  /// building=roof, building:part=roof: a roof on open sides (a canopy, a shelter).
  bool open_sides = false;
  std::optional<double> roof_height;  // roof:height, else roof:levels x level height
  std::string lost;                   // why no footprint of positive area is left, or empty
  Ring lost_outline;           // a lost geometry: the convex hull of its positions (empty: no area)
  std::string refused_height;  // a height or level count given but not positive, as given
  std::string payload;         // ReadOptions::payload_key's property
  /// OSM's location=underground, Overture's is_underground: a car park or station below the
  /// street, mapped as a building: its footprint is no wall anyone sees.
  bool underground = false;
};

std::string lower_case(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

const Json& properties_of(const Json& feature) {
  static const Json none = Json::object();
  return feature.contains("properties") && feature["properties"].is_object() ? feature["properties"]
                                                                             : none;
}

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

  static bool given(const Json& props, const char* key) {
    return props.contains(key) && !props[key].is_null();
  }

  // Datasets write -1 or 0 where they do not know a building's height (footprint datasets
  // do). No building is that tall, so such a value is no height at all: the next key, the
  // levels, --default-height or, failing all, the tallest plausible building decide (thesis 7.1:
  // what is unknown is as tall as it may be), never a building 0 m tall that anything hides.
  std::optional<double> positive(const Json& props, const char* key, Feature& f) {
    std::optional<double> v = length(props, key, f.id);
    if (v && !(*v > 0)) {
      if (f.refused_height.empty()) f.refused_height = std::string(key) + " " + props[key].dump();
      return std::nullopt;
    }
    return v;
  }

  std::size_t with_height_field = 0;  ///< features that have options.height_field

  void read(const Json& props, Feature& f) {
    if (!options.height_field.empty()) {  // the dataset's own name for it comes first
      if (given(props, options.height_field.c_str())) ++with_height_field;
      f.height = positive(props, options.height_field.c_str(), f);
    }
    for (const char* key : {"height", "building:height", "measuredHeight"})
      if (!f.height) f.height = positive(props, key, f);
    // OSM's keys, then Overture Maps' (its buildings theme writes num_floors, min_floor,
    // roof_height and roof_shape, with the same meanings and roof shapes as OSM's).
    std::optional<double> levels = positive(props, "building:levels", f);
    if (!levels) levels = positive(props, "num_floors", f);
    if (levels) f.levels_height = *levels * options.level_height;
    if (!f.height && f.levels_height) {
      f.height = f.levels_height;
      f.height_from_levels = true;
    }
    const char* shape_key = given(props, "roof:shape") ? "roof:shape" : "roof_shape";
    f.underground = string_member(props, "location") == "underground" ||
                    (props.contains("is_underground") && props["is_underground"] == true);
    f.roof_shape = lower_case(string_member(props, shape_key));
    if (given(props, shape_key) && !props[shape_key].is_string())
      f.roof_shape = props[shape_key].dump();  // "roof:shape": 9 is no shape we know: not flat
    for (const char* key : {"roof:direction", "roof_direction"}) {
      if (!given(props, key) || f.roof_direction) continue;
      const Json& v = props[key];
      f.roof_direction = v.is_number()   ? roof_direction(v.dump())
                         : v.is_string() ? roof_direction(v.get<std::string>())
                                         : std::nullopt;
      if (!f.roof_direction)
        report.warnings.push_back(file + ": " + f.id + ": cannot read " + key + " " + v.dump() +
                                  "; ignored");
    }
    for (const char* key : {"roof:orientation", "roof_orientation"}) {
      const std::string v = lower_case(string_member(props, key));
      if (v == "along") f.roof_ridge = RidgeOrientation::Along;
      if (v == "across") f.roof_ridge = RidgeOrientation::Across;
    }
    for (const char* key : {"building", "building:part"})
      if (string_member(props, key) == "roof") f.open_sides = true;
    if (std::optional<double> r = length(props, "roof:height", f.id))
      f.roof_height = *r, f.roof_height_in_metres = true;
    else if (std::optional<double> o = length(props, "roof_height", f.id))
      f.roof_height = *o, f.roof_height_in_metres = true;
    else if (std::optional<double> l = length(props, "roof:levels", f.id))
      f.roof_height = *l * options.level_height;
    if (f.roof_height && *f.roof_height < 0) f.roof_height.reset();
    if (std::optional<double> m = length(props, "min_height", f.id)) {
      f.min_height = *m;
    } else if (std::optional<double> l = length(props, "building:min_level", f.id)) {
      f.min_height = *l * options.level_height;
    } else if (std::optional<double> o = length(props, "min_floor", f.id)) {
      f.min_height = *o * options.level_height;
    } else if (given(props, "min_height") || given(props, "building:min_level") ||
               given(props, "min_floor")) {
      // An unreadable base must not become the ground: the part may start anywhere above it.
      f.base_unknown = true;
      report.warnings.push_back(file + ": " + f.id +
                                ": where the part starts is unknown; it gives no occluder");
    }
  }
};

Feature read_feature(const Json& feature, std::size_t index, const std::string& file,
                     const LocalFrameMapping& mapping, HeightReader& heights, ReadReport& report) {
  Feature f;
  f.id = feature_id(feature, index);
  const Json& g = feature["geometry"];
  for (const Json* poly : polygons_of(g, file, f.id, heights.options.strict, report)) {
    std::vector<Ring> rings;
    for (const Json& ring : *poly) {
      if (!ring.is_array())
        throw InputError(InputProblem::BadStructure, file, f.id, "ring is not an array");
      Ring r;
      for (const Json& p : ring) {
        const Vec2 in = position(p, file, f.id);
        const auto local = mapping.to_local(in.x, in.y, 0);
        r.push_back({local[0], local[1]});
        f.box.extend(r.back());
      }
      rings.push_back(std::move(r));
    }
    for (Polygon& p :
         clean_polygon(std::move(rings), {file, f.id, true, heights.options.strict}, report))
      f.polygons.push_back(std::move(p));
  }
  if (f.polygons.empty()) f.lost = "no footprint of positive area left after repair";
  const Json& props = properties_of(feature);
  f.payload = payload_of(props, heights.options.payload_key);
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

// The feature's height, or nullopt when it has none and no default is given.
std::optional<double> feature_height(Feature& f, const ReadOptions& options, ReadReport& report) {
  if (f.height) {
    if (f.height_from_levels) ++report.level_heights;
    return *f.height;
  }
  if (!options.default_height) return std::nullopt;
  ++report.default_heights;
  f.height = *options.default_height;
  return *f.height;
}

// The input's own surfaces of a footprint prism from `base` to `top`: walls, top and bottom.
void add_prism_surfaces(const Polygon& p, double base, double top, bool blocks, bool bottom,
                        std::vector<Surface3>& out) {
  auto ring3 = [](const Ring& r, double z) {
    std::vector<Vec3> v;
    for (Vec2 q : r) v.push_back({q.x, q.y, z});
    return v;
  };
  Surface3 top_face, bottom_face;
  top_face.rings.push_back(ring3(p.outer, top));
  bottom_face.rings.push_back(ring3(p.outer, base));
  for (const Ring& h : p.holes) {
    top_face.rings.push_back(ring3(h, top));
    bottom_face.rings.push_back(ring3(h, base));
  }
  top_face.blocks = bottom_face.blocks = blocks;
  out.push_back(std::move(top_face));
  if (bottom) out.push_back(std::move(bottom_face));
  for_each_edge(p, [&](Vec2 a, Vec2 b) {
    out.push_back(
        {{{{a.x, a.y, base}, {b.x, b.y, base}, {b.x, b.y, top}, {a.x, a.y, top}}}, blocks});
  });
}

// The top of the walls (eaves) and of the roof (ridge) of a feature of height `h`, both from the
// ground. OSM's height (and --default-height) is the roof's top; building:levels counts the
// storeys below the roof (OSM: roof:levels are extra), so a height from levels is the eaves.
// A roof other than flat (roof:shape given and not "flat", or a roof:height / roof:levels with no
// roof:shape) ends its walls roof:height below the top. With neither roof:height nor roof:levels,
// building:levels x level height is the eaves when it is lower than `height`; else nothing tells
// where the walls end, and the eaves are taken as min_height: no occluder volume comes from the
// roof part (thesis 7.1: better no occluder than one through open air).
struct WallTop {
  double eaves = 0, top = 0;
  bool cut = false;  // the occluder ends below `height`
};

WallTop wall_top(const Feature& f, double h) {
  const double roof = f.roof_height.value_or(0);
  if (f.height_from_levels) return {h, h + roof, false};
  const bool pitched = f.roof_shape.empty() ? roof > 0 : f.roof_shape != "flat";
  if (!pitched) return {h, h, false};
  double eaves = f.min_height;
  if (f.roof_height)
    eaves = h - roof;
  else if (f.levels_height && *f.levels_height < h)
    eaves = *f.levels_height;
  eaves = std::clamp(eaves, std::min(f.min_height, h), h);
  return {eaves, h, eaves < h};
}

// Adds a feature's box, surfaces and occluders to its object; returns why it cannot occlude
// (unknown height, geometry beyond repair), or an empty string.
std::string add_occluders(Feature& f, CityObject& o, const std::string& file,
                          const ReadOptions& options, ReadReport& report) {
  const std::optional<double> height = feature_height(f, options, report);
  // Unknown: as tall as a building may be (ReadOptions::max_height).
  const WallTop w = height ? wall_top(f, *height) : WallTop{0, options.max_height, false};
  const double h = w.top;
  if (h - f.min_height > options.max_height) {
    char what[160];
    std::snprintf(what, sizeof what,
                  "height %.0f m is more than the tallest plausible (--max-height %.0f m)", h,
                  options.max_height);
    throw InputError(InputProblem::Implausible, file, f.id, what);
  }
  o.bbox.extend(f.box.min, f.min_height);
  o.bbox.extend(f.box.max, std::max(h, f.min_height));
  // Its walls and top lie below the ground: an occluder or a blocking surface at street level
  // would hide what is in front of it from the bake and from the validator alike.
  if (f.underground)
    return file + ": " + f.id + ": underground (location=underground or is_underground)";
  if (!f.lost.empty()) return file + ": " + f.id + ": " + f.lost;
  const std::string none = "no " +
                           (options.height_field.empty() ? "" : options.height_field + ", ") +
                           "height, building:height, measuredHeight, building:levels or "
                           "num_floors";
  if (!height && options.strict)
    throw InputError(InputProblem::MissingHeight, file, f.id,
                     none + " (give a default height; --strict refuses objects of unknown height)");
  if (!height)
    return file + ": " + f.id + ": " + none +
           (f.refused_height.empty() ? ""
                                     : " (" + f.refused_height + " is no height: not positive)") +
           " (and no --default-height)";
  // A roof on open sides (building=roof: a canopy, a petrol station's roof, a shelter): no wall
  // stands under it, so it gives no occluder (thesis 7.1), and in validation its prism is a
  // target only: sight lines pass under it.
  if (f.open_sides) {
    for (const Polygon& p : f.polygons)
      add_prism_surfaces(p, f.min_height, h, false, true, o.surfaces);
    ++report.open_roofs;
    return {};
  }
  // A roof of its own above the walls (cut from `height` to the eaves, or roof:levels above
  // building:levels): the walls stand up to the eaves for sure; the roof above them has a shape
  // the tags do not give, so its prism only bounds where the building may be (thesis 7.1): the
  // validator aims at it but never lets it block. Where roof:shape names a roof that
  // shaped_roof models, between eaves and top that the tags give in metres (`height`, and
  // roof:height below it), its faces and the walls above the eaves are surfaces the building
  // surely has (RoofShapes.hpp): they block, and the prisms under the faces occlude
  // (ReadOptions::sloped_roofs).
  const bool roof_above = w.top > w.eaves;
  const bool measured = f.height && !f.height_from_levels && f.roof_height_in_metres && w.cut &&
                        w.eaves > f.min_height;
  const RoofShapeTags tags{f.roof_shape, f.roof_direction, f.roof_ridge};
  for (const Polygon& p : f.polygons) {
    const double wall = roof_above ? std::max(w.eaves, f.min_height) : h;
    add_prism_surfaces(p, f.min_height, wall, true, true, o.surfaces);
    if (wall < h) add_prism_surfaces(p, wall, h, false, false, o.surfaces);
    if (!measured || !options.sloped_roofs || f.base_unknown) continue;
    const std::optional<ShapedRoof> roof = shaped_roof(p, tags, wall, h);
    if (!roof) continue;
    ++report.roof_shapes;
    std::vector<RoofFace> faces;
    for (const std::vector<Vec3>& face : roof->faces) {
      o.surfaces.push_back({{face}, true});
      Ring plan;
      for (const Vec3& v : face) plan.push_back({v[0], v[1]});
      if (signed_area2(plan) < 0) std::reverse(plan.begin(), plan.end());
      faces.push_back(roof_face({face}, {Polygon{std::move(plan), {}}}));
    }
    for (const std::vector<Vec3>& wall_above : roof->walls)
      o.surfaces.push_back({{wall_above}, true});
    // Occluders stand on the ground (thesis 7.3.2): a raised part gives none (below).
    if (f.min_height > 0) continue;
    for (RoofPrism& prism : roof_prisms({p}, 0.0, faces, wall))
      o.roof_prisms.push_back(std::move(prism));
  }
  // Parts that do not reach the ground (min_height > 0, or a base we cannot read) leave open
  // space below them; the occluders downstream are 2.5D prisms standing on the ground, so such
  // parts give none (never volume below min_height).
  if (f.min_height > 0 || f.base_unknown) return {};
  if (w.cut) ++report.roof_eaves;
  if (w.eaves <= 0) return {};
  for (const Polygon& p : f.polygons) o.occluders.push_back({p, 0.0, w.eaves});
  return {};
}

/// Every position of a feature's polygons, as given, whatever rings they fail to make.
std::vector<Vec2> raw_positions(const Json& feature, const std::string& file,
                                const std::string& id) {
  std::vector<Vec2> out;
  for (const Json* poly : polygon_arrays(feature["geometry"], file, id))
    if (poly->is_array())
      for (const Json& ring : *poly)
        if (ring.is_array())
          for (const Json& p : ring) out.push_back(position(p, file, id));
  return out;
}

}  // namespace

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
    for (const Json* poly : polygon_arrays(f["geometry"], file, id))
      if (poly->is_array())
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
    scan.kind =
        is_geographic_crs(declared) ? LocalFrame::Kind::Geographic : LocalFrame::Kind::Projected;
    scan.note = file + ": reference system " + declared + " from the \"crs\" member";
  } else {
    scan.kind = lonlat_range ? LocalFrame::Kind::Geographic : LocalFrame::Kind::Projected;
    scan.note =
        file + (lonlat_range ? ": no \"crs\"; coordinates lie within lon/lat range, read as WGS84"
                             : ": no \"crs\"; coordinates exceed lon/lat range, read as projected "
                               "metres");
  }
  if (scan.kind == LocalFrame::Kind::Geographic && !lonlat_range && !scan.bounds.empty())
    throw InputError(InputProblem::UnknownCrs, file, "",
                     "coordinates are read as WGS84 lon/lat but exceed its range");
  scan.crs = declared.empty() && scan.kind == LocalFrame::Kind::Geographic ? "OGC:CRS84" : declared;
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
      if (feature.contains(kUnreadableMember))  // an OSM area that could not be built
        throw InputError(InputProblem::InvalidGeometry, file, feature_id(feature, i),
                         string_member(feature, kUnreadableMember));
      Feature f = read_feature(feature, i, file, mapping, heights, report);
      if (f.box.empty()) {  // rings without positions: nothing to place it by
        report.warnings.push_back(file + ": " + f.id + ": no coordinates: skipped");
        return;
      }
      (f.part ? parts : buildings).push_back(std::move(f));
    } catch (const InputError& e) {
      if (options.strict || e.problem() != InputProblem::InvalidGeometry) throw;
      // Beyond repair, yet still a building: kept over the box of its coordinates.
      Feature f;
      f.id = feature_id(feature, i);
      f.payload = payload_of(properties_of(feature), options.payload_key);
      heights.read(properties_of(feature), f);  // the geometry is lost, not what the tags say
      std::vector<Vec2> points = raw_positions(feature, file, f.id);
      if (points.empty()) {
        report.warnings.push_back(std::string(e.what()) + " (no coordinates: skipped)");
        return;
      }
      for (Vec2& c : points) {
        const auto local = mapping.to_local(c.x, c.y, 0);
        c = {local[0], local[1]};
        f.box.extend(c);
      }
      // Where the building stands: its points' hull, not their box, is taken out of free space,
      // so a long or diagonal ruin does not take the streets beside it out of the view cells.
      f.lost_outline = convex_hull(points);
      f.lost = e.what();
      buildings.push_back(std::move(f));
    }
  });
  if (!options.height_field.empty() && heights.with_height_field == 0)
    report.warnings.push_back(file + ": --height-field " + options.height_field +
                              ": no feature has this property, field or tag");

  // Attach each part to the smallest building outline that contains it.
  std::vector<std::vector<Feature*>> parts_of(buildings.size());
  std::vector<Feature*> orphans;
  for (Feature& p : parts) {
    const Vec2 q =
        p.polygons.empty() ? 0.5 * (p.box.min + p.box.max) : interior_point(p.polygons.front());
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
    o.payload = f.payload;  // a building's own; its parts' values are not merged in
    o.footprint = f.polygons;
    if (o.footprint.empty() && !f.lost_outline.empty()) o.footprint = {Polygon{f.lost_outline, {}}};
    o.ground_z = 0;
    return o;
  };
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    Feature& f = buildings[b];
    CityObject o = object_of(f);
    std::string why;
    if (parts_of[b].empty()) {
      why = add_occluders(f, o, file, options, report);
    } else {
      for (Feature* p : parts_of[b])
        if (std::string w = add_occluders(*p, o, file, options, report); why.empty()) why = w;
      // The outline still bounds the object; its height only matters when it has its own.
      const double h = f.height ? wall_top(f, *f.height).top : o.bbox.zmax;
      o.bbox.extend(f.box.min, 0.0);
      o.bbox.extend(f.box.max, h);
    }
    city.objects.push_back(why.empty() ? std::move(o) : non_occluding(std::move(o), why, report));
  }
  for (Feature* p : orphans) {
    CityObject o = object_of(*p);
    const std::string why = add_occluders(*p, o, file, options, report);
    city.objects.push_back(why.empty() ? std::move(o) : non_occluding(std::move(o), why, report));
  }
}

}  // namespace urbanpvs::geometry::detail
