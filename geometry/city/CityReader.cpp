// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/CityReader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "BoxGrid.hpp"
#include "CityReaders.hpp"
#include "GdalHandles.hpp"
#include "InputReprojection.hpp"
#include "urbanpvs/geometry/city/DemTerrain.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry {
namespace detail {

std::string string_member(const Json& obj, const char* key) {
  if (!obj.is_object()) return {};
  const auto it = obj.find(key);
  return it != obj.end() && it->is_string() ? it->get<std::string>() : std::string();
}

std::string payload_of(const Json& attributes, const std::string& key) {
  if (key.empty() || !attributes.is_object()) return {};
  const auto it = attributes.find(key);
  if (it == attributes.end() || it->is_null()) return {};
  // The PVS file's payloads must be UTF-8, but OSM PBF tags are not checked by libosmium (JSON
  // input is, by the parser): invalid bytes become U+FFFD, by nlohmann's own dump.
  const std::string text = it->dump(-1, ' ', false, Json::error_handler_t::replace);
  return it->is_string() ? Json::parse(text).get<std::string>() : text;
}

double json_number(const Json& v, const std::string& file, const std::string& feature,
                   const char* what) {
  if (!v.is_number())
    throw InputError(InputProblem::BadStructure, file, feature,
                     std::string(what) + " is not a number");
  const double d = v.get<double>();
  if (!std::isfinite(d))
    throw InputError(InputProblem::InvalidGeometry, file, feature,
                     std::string(what) + " is NaN or infinite");
  return d;
}

std::string normalise_crs(const std::string& name, const std::string& file) {
  auto code_after = [&](const std::string& marker) -> std::string {
    const auto pos = name.find(marker);
    if (pos == std::string::npos) return {};
    std::string rest = name.substr(pos + marker.size());
    // "EPSG/0/7415", "EPSG::7415", "EPSG:6.6:4326", "EPSG:7415": the code is the last field.
    const auto cut = rest.find_last_of("/:");
    std::string code = cut == std::string::npos ? rest : rest.substr(cut + 1);
    if (code.empty() || code.find_first_not_of("0123456789") != std::string::npos) return {};
    return code;
  };
  if (name.find("CRS84") != std::string::npos) return "OGC:CRS84";
  // A compound URN ("urn:ogc:def:crs,crs:EPSG::25832,crs:EPSG::7837") names the horizontal
  // system first: its code, not the height system's.
  if (const auto comma = name.find(",crs:"); comma != std::string::npos) {
    const auto end = name.find(',', comma + 1);
    const std::string first =
        name.substr(comma + 1, end == std::string::npos ? end : end - comma - 1);
    if (first.find("EPSG") != std::string::npos) return normalise_crs(first, file);
  }
  if (std::string code = code_after("EPSG"); !code.empty()) return "EPSG:" + code;
  if (std::string identified = identify_crs(name); !identified.empty()) return identified;
  throw InputError(InputProblem::UnknownCrs, file, "", "cannot interpret \"" + name + "\"");
}

CityObject non_occluding(CityObject o, const std::string& why, ReadReport& report) {
  o.occludes = false;
  o.occluders.clear();
  // A footprint that survived (only the height is unknown) still says where the building is;
  // else its box does.
  const Box2& b = o.bbox.xy;
  if (o.footprint.empty() && !b.empty() && b.area() > 0) o.footprint = {Polygon{b.corners(), {}}};
  report.non_occluding.push_back(why + " (kept as an object that occludes nothing)");
  return o;
}

void check_plausible(const CityObject& o, const ReadOptions& options, const std::string& file) {
  const double h = o.bbox.zmax - o.ground_z;
  if (h > options.max_height * (1 + 1e-9)) {  // objects of unknown height reach it exactly
    char what[160];
    std::snprintf(what, sizeof what,
                  "building is %.0f m tall, more than the tallest plausible (--max-height %.0f m)",
                  h, options.max_height);
    throw InputError(InputProblem::Implausible, file, o.source_id, what);
  }
}

bool is_geographic_crs(const std::string& c) {
  return c == "OGC:CRS84" || c == "EPSG:4326" || c == "EPSG:4979";
}

std::ifstream open_input_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(InputProblem::Unreadable, path, "",
                     std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputProblem::Unreadable, path, "", "cannot open file");
  return in;
}

bool has_extension(const std::string& path, const char* ext) {
  const std::size_t n = std::strlen(ext);
  if (path.size() < n) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(path[path.size() - n + i])) != ext[i]) return false;
  return true;
}

std::string json_error_text(const nlohmann::json::exception& e) {
  std::string what = e.what();
  if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
  return what;
}

std::string read_input_file(const std::string& path) {
  std::ifstream in = open_input_file(path);
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InputError(InputProblem::Unreadable, path, "", "read failed");
  return s.str();
}

}  // namespace detail

namespace {

using detail::Json;

enum class Format { CityJson, GeoJson };

Json parse(std::string_view text, const std::string& name) {
  if (detail::is_xml(text)) return detail::citygml_to_cityjson(text, name);
  if (std::optional<Json> joined = detail::join_json_sequence(text, name))
    return std::move(*joined);
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() carries "line L, column C"; the byte offset is added.
    throw InputError(InputProblem::InvalidJson, name, "",
                     detail::json_error_text(e) + " (byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::exception& e) {
    // e.g. out_of_range.406: a number too large for a double (1e400).
    throw InputError(InputProblem::InvalidJson, name, "", detail::json_error_text(e));
  }
}

// A value of a type that no check of the readers expected (an index where an object stands, a
// string for a number) surfaces as nlohmann's exception from deep inside a reader. It is still
// the input's fault: refused as its structure, naming the file, never an internal failure or an
// abort of a tool that only catches input errors.
template <class Read>
auto refusing_type_errors(const std::string& name, Read&& read) {
  try {
    return read();
  } catch (const Json::exception& e) {
    throw InputError(InputProblem::BadStructure, name, "",
                     std::string("a value of an unexpected type (") + e.what() + ")");
  }
}

// A text file's city: CityGML, CityJSON (or a sequence of it), GeoJSON, or OpenStreetMap data
// from the Overpass API in JSON, which the OSM reader's assembly takes (OverpassJson.cpp).
Json parse_city(std::string_view text, const std::string& name, ReadReport& report) {
  Json doc = parse(text, name);
  if (detail::is_overpass_json(doc))
    return refusing_type_errors(name,
                                [&] { return detail::read_overpass_json(doc, name, report); });
  return doc;
}

Format detect(const Json& doc, const std::string& name) {
  if (!doc.is_object() || !doc.contains("type") || !doc["type"].is_string())
    throw InputError(InputProblem::UnsupportedFormat, name, "",
                     "neither CityJSON, GeoJSON nor Overpass JSON (no top-level \"type\" or "
                     "\"elements\")");
  const std::string type = doc["type"].get<std::string>();
  if (type == "CityJSON") return Format::CityJson;
  if (type == "FeatureCollection" || type == "Feature") return Format::GeoJson;
  if (type == "CityJSONFeature")  // its vertices mean nothing without the header's transform
    throw InputError(InputProblem::UnsupportedFormat, name, "",
                     "a lone CityJSONFeature: a CityJSON text sequence (.city.jsonl) starts "
                     "with the CityJSON object that holds its transform");
  throw InputError(InputProblem::UnsupportedFormat, name, "",
                   "top-level type \"" + type + "\" is neither CityJSON nor a GeoJSON feature");
}

// The terrain under footprints: the lowest and highest TIN height over a polygon. The TIN is
// linear on each triangle, so both lie at a footprint corner, at a TIN vertex inside the
// footprint, or where a TIN edge crosses a footprint edge; all three are visited.
class TerrainUnder {
 public:
  explicit TerrainUnder(const Terrain& t) : t_(t) {
    std::vector<Box2> boxes;
    for (const Triangle3& tri : t.triangles) {
      Box2 b;
      for (const auto& v : tri.v) b.extend(Vec2{v[0], v[1]});
      boxes.push_back(b);
    }
    grid_ = detail::BoxGrid(boxes);
  }

  struct Range {
    double lo = INFINITY, hi = -INFINITY;
    bool partial = false;  // a footprint corner lies off the TIN: its ground there is unknown
    bool empty() const { return lo > hi; }
    void add(double z) { lo = std::min(lo, z), hi = std::max(hi, z); }
  };

  Range under(const std::vector<Polygon>& polys) const {
    Range r;
    for (const Polygon& p : polys) {
      for_each_edge(p, [&](Vec2 a, Vec2 b) {
        if (std::optional<double> z = at(a))
          r.add(*z);
        else
          r.partial = true;
        Box2 eb;
        eb.extend(a);
        eb.extend(b);
        for_each_near(eb, [&](const Triangle3& tri) {
          for (int k = 0; k < 3; ++k) crossing(a, b, tri.v[k], tri.v[(k + 1) % 3], r);
        });
      });
      for_each_near(bounds(p), [&](const Triangle3& tri) {
        for (const auto& v : tri.v)
          if (inside(p, Vec2{v[0], v[1]})) r.add(v[2]);
      });
    }
    return r;
  }

 private:
  using V3 = Vec3;

  // The TIN's height at q, or nullopt off the TIN.
  std::optional<double> at(Vec2 q) const {
    for (std::uint32_t i : grid_.at(q)) {
      const auto& v = t_.triangles[i].v;
      const Vec2 p0{v[0][0], v[0][1]}, p1{v[1][0], v[1][1]}, p2{v[2][0], v[2][1]};
      const double d = cross(p1 - p0, p2 - p0);
      if (std::abs(d) < 1e-12) continue;
      const double l1 = cross(q - p0, p2 - p0) / d, l2 = cross(p1 - p0, q - p0) / d;
      const double l0 = 1 - l1 - l2, eps = 1e-9;
      if (l0 >= -eps && l1 >= -eps && l2 >= -eps) return l0 * v[0][2] + l1 * v[1][2] + l2 * v[2][2];
    }
    return std::nullopt;
  }

  // Adds the TIN edge pq's height where it crosses the footprint edge ab.
  static void crossing(Vec2 a, Vec2 b, const V3& p3, const V3& q3, Range& r) {
    const Vec2 p{p3[0], p3[1]}, q{q3[0], q3[1]};
    const Vec2 ab = b - a, pq = q - p;
    const double d = cross(ab, pq);
    if (std::abs(d) < 1e-12) return;  // parallel: the endpoints decide
    const double s = cross(p - a, pq) / d, u = cross(p - a, ab) / d;
    if (s < 0 || s > 1 || u < 0 || u > 1) return;
    r.add(p3[2] + u * (q3[2] - p3[2]));
  }

  template <class F>
  void for_each_near(const Box2& b, F&& f) const {
    if (grid_.empty() || !b.overlaps(grid_.extent())) return;
    for (std::int64_t y = grid_.clamp_y(b.min.y); y <= grid_.clamp_y(b.max.y); ++y)
      for (std::int64_t x = grid_.clamp_x(b.min.x); x <= grid_.clamp_x(b.max.x); ++x)
        for (std::uint32_t i : grid_.bucket(x, y)) f(t_.triangles[i]);
  }

  const Terrain& t_;
  detail::BoxGrid grid_;
};

// GeoJSON heights are above the ground; with a terrain (a CityJSON TINRelief read in the same
// call, before or after) the ground is the terrain under the footprint, not z = 0. The
// occluder stands on the LOWEST ground under it, so its top (lowest ground + eaves) never
// exceeds the real building's (thesis 7.1); the box, which says where the building may be seen,
// reaches the HIGHEST ground + height (as tall as it may be). The surfaces (the validator's
// ground truth) stand on the lowest ground: OSM measures height from the lowest point where the
// building meets the ground.
void place_on_terrain(City& city, const std::vector<bool>& relative) {
  const TerrainUnder terrain(city.terrain);
  std::size_t off = 0, partial = 0;
  std::string off_id, partial_id;
  for (std::size_t i = 0; i < city.objects.size(); ++i) {
    if (!relative[i]) continue;
    CityObject& o = city.objects[i];
    std::vector<Polygon> where = o.footprint;
    for (const OccluderPrism& p : o.occluders) where.push_back(p.footprint);
    const Box2& b = o.bbox.xy;
    if (where.empty() && !b.empty()) where.push_back({b.corners(), {}});
    const TerrainUnder::Range r = terrain.under(where);
    if (r.empty()) {
      if (off++ == 0) off_id = o.source_id;
      continue;
    }
    if (r.partial && partial++ == 0) partial_id = o.source_id;
    o.ground_z += r.lo;
    for (OccluderPrism& p : o.occluders) p.ground_z += r.lo, p.top_z += r.lo;
    for (RoofPrism& p : o.roof_prisms) p.ground_z += r.lo, p.z0 += r.lo;
    for (Surface3& s : o.surfaces)
      for (auto& ring : s.rings)
        for (auto& v : ring) v[2] += r.lo;
    o.bbox.zmin += r.lo;
    o.bbox.zmax += r.hi;
    ++city.report.on_terrain;
  }
  if (off)
    city.report.warnings.push_back(std::to_string(off) + " GeoJSON building(s) (first " + off_id +
                                   ") lie off the terrain: they stand at z = 0");
  if (partial)
    city.report.warnings.push_back(
        std::to_string(partial) + " GeoJSON building(s) (first " + partial_id +
        ") lie partly off the terrain: their ground is taken from the terrain under the rest");
}

struct Reader {
  const ReadOptions& options;
  City city;
  std::unique_ptr<LocalFrameMapping> mapping;
  std::vector<bool> relative;  // per object: heights relative to the ground (GeoJSON)

  std::vector<std::pair<Json, std::string>> waiting;  // documents without a building, as yet
  bool placing_without_buildings = false;

  void add(Json doc, const std::string& name) {
    refusing_type_errors(name, [&] { add_document(doc, name); });
  }

  // The documents that waited for a frame, in their order (the first one places the frame when
  // no file has a building: the city is then refused as empty).
  void add_waiting() {
    placing_without_buildings = true;
    for (auto& [doc, name] : waiting) add(std::move(doc), name);
    waiting.clear();
  }

  void add_document(Json& doc, const std::string& name) {
    const Format format = detect(doc, name);
    if (format == Format::CityJson) detail::expand_geometry_instances(doc, name);
    auto scan_of = [&](const Json& d) {
      return format == Format::CityJson ? detail::scan_cityjson(d, name)
                                        : detail::scan_geojson(d, name, options);
    };
    detail::InputScan scan = scan_of(doc);
    // OpenStreetMap is WGS84 lon/lat by definition, whatever it holds: a file without a
    // building (streets only, or nothing in the area) is no file in another system.
    const bool osm = doc.contains(detail::kStreetsMember);
    if (osm) {
      scan.kind = LocalFrame::Kind::Geographic;
      scan.crs = "OGC:CRS84";
      scan.note = name + ": OpenStreetMap, WGS84 lon/lat";
    }
    // The frame is placed by the buildings' coordinates: a file without any waits for one with.
    if (!mapping && scan.bounds.empty() && !placing_without_buildings) {
      waiting.emplace_back(std::move(doc), name);
      return;
    }
    // Every stage works in metres (ε, the cell edges, the eye band, the PVS file's frame): feet,
    // Mercator "metres" and degrees on another datum are transformed into WGS84 lon/lat first,
    // unless the user has said how to read GeoJSON's coordinates (--coordinates).
    if (format == Format::CityJson || options.coordinates == ReadOptions::Coordinates::Auto)
      if (std::optional<detail::Reprojection> r = detail::reprojection_for(scan.crs, name)) {
        if (format == Format::CityJson)
          detail::reproject_cityjson(doc, *r, name);
        else
          detail::reproject_geojson(doc, *r, name);
        scan = scan_of(doc);
        scan.note = name + ": " + r->from + " transformed to WGS84 lon/lat";
      }
    if (!mapping) {
      city.frame = choose_local_frame(scan.kind, scan.crs, scan.bounds);
      city.report.coordinate_note = scan.note;
      mapping = std::make_unique<LocalFrameMapping>(city.frame);
    } else if (scan.kind != city.frame.kind ||
               (!scan.crs.empty() && !city.frame.crs.empty() && scan.crs != city.frame.crs)) {
      throw InputError(InputProblem::UnknownCrs, name, "",
                       "reference system " + (scan.crs.empty() ? "(none)" : scan.crs) +
                           " differs from " + city.sources.front() + "'s " +
                           (city.frame.crs.empty() ? "(none)" : city.frame.crs));
    }
    if (format == Format::CityJson)
      detail::load_cityjson(doc, name, *mapping, options, city);
    else
      detail::load_geojson(doc, name, *mapping, options, city);
    if (doc.contains(detail::kStreetsMember)) {
      StreetNetwork more =
          detail::osm_streets(doc[detail::kStreetsMember], name, *mapping, city.report);
      for (StreetLine& l : more.lines) city.streets.lines.push_back(std::move(l));
      for (Polygon& a : more.areas) city.streets.areas.push_back(std::move(a));
    }
    relative.resize(city.objects.size(), format == Format::GeoJson);
    city.sources.push_back(name);
  }

  // The DEM, resampled over the buildings and streets and kDemMargin around them; beyond that
  // the ground model takes the height of the nearest TIN point.
  void read_terrain(const std::string& name) {
    constexpr double kDemMargin = 250;  // [Units: m] beyond any default view-cell region
    Box2 area = city.bounds().xy;
    for (const StreetLine& l : city.streets.lines)
      for (Vec2 p : l.points) area.extend(p);
    for (const Polygon& a : city.streets.areas) area.extend(bounds(a));
    if (!city.terrain.empty())
      city.report.warnings.push_back(options.terrain_path + " replaces the TINRelief of " + name);
    DemSummary s;
    city.terrain = read_dem_terrain(options.terrain_path, city.frame, area.grown(kDemMargin), &s);
    char note[400];
    std::snprintf(note, sizeof note,
                  "%s (%s, %s, %d x %d pixels of %.1f x %.1f m), resampled every %.1f m: %d x %d "
                  "nodes, %zu filled from neighbours, heights %.1f .. %.1f m",
                  options.terrain_path.c_str(), s.driver.c_str(), s.crs.c_str(), s.raster_columns,
                  s.raster_rows, s.pixel_x, s.pixel_y, s.spacing, s.columns, s.rows, s.filled,
                  s.zmin, s.zmax);
    city.report.terrain_note = note;
    for (std::string& w : s.warnings) city.report.warnings.push_back(std::move(w));
  }

  City finish(const std::string& name) {
    if (city.objects.empty()) {
      // Say what the files held instead: a city of GenericCityObjects or of roads is refused
      // for what it is, not for being empty.
      std::string held;
      for (const auto& [type, count] : city.report.ignored_types)
        held += (held.empty() ? "" : ", ") + std::to_string(count) + " " + type;
      throw InputError(InputProblem::EmptyCity, name, "",
                       held.empty() ? "no building found"
                                    : "no building found (only objects of types that are not "
                                      "read: " +
                                          held + ")");
    }
    const Box2 b = city.bounds().xy;
    const double extent = std::max(b.max.x - b.min.x, b.max.y - b.min.y);
    if (extent > options.max_extent) {
      // Most often small projected coordinates that the values made look like degrees.
      const bool guessed_degrees = city.frame.kind == LocalFrame::Kind::Geographic &&
                                   options.coordinates == ReadOptions::Coordinates::Auto;
      char what[256];
      std::snprintf(what, sizeof what,
                    "the buildings span %.0f km, more than a city can (%.0f km)%s", extent / 1000,
                    options.max_extent / 1000,
                    guessed_degrees ? "; its coordinates were read as lon/lat degrees: give "
                                      "--coordinates projected if they are metres"
                                    : "");
      throw InputError(InputProblem::Implausible, name, "", what);
    }
    if (!options.terrain_path.empty()) read_terrain(name);
    // After every file: the terrain may come after the buildings standing on it.
    if (!city.terrain.empty() &&
        std::find(relative.begin(), relative.end(), true) != relative.end())
      place_on_terrain(city, relative);
    for (std::size_t i = 0; i < city.objects.size(); ++i)
      city.objects[i].index = static_cast<std::uint32_t>(i);
    city.payload_key = options.payload_key;
    if (!options.payload_key.empty()) {
      const auto with = std::count_if(city.objects.begin(), city.objects.end(),
                                      [](const CityObject& o) { return !o.payload.empty(); });
      if (with == 0)
        city.report.warnings.push_back("--payload " + options.payload_key +
                                       ": no object has this attribute, property or tag");
    }
    return std::move(city);
  }
};

}  // namespace

City read_city(const std::vector<std::string>& paths, const ReadOptions& options) {
  if (paths.empty()) throw InputError(InputProblem::EmptyCity, "(no file)", "", "no input file");
  Reader reader{options, {}, {}, {}, {}, false};
  for (const std::string& p : paths)
    reader.add(detail::is_osm_file(p) ? detail::read_osm(p, reader.city.report)
               : detail::is_gis_vector_file(p)
                   ? detail::read_gis_vector(p, options, reader.city.report)
                   : parse_city(detail::read_input_file(p), p, reader.city.report),
               p);
  reader.add_waiting();
  return reader.finish(paths.back());
}

City read_city_text(std::string_view text, const std::string& name, const ReadOptions& options) {
  Reader reader{options, {}, {}, {}, {}, false};
  reader.add(parse_city(text, name, reader.city.report), name);
  reader.add_waiting();
  return reader.finish(name);
}

}  // namespace urbanpvs::geometry
