// SPDX-License-Identifier: GPL-3.0-or-later
// CityJSON 1.0/1.1/2.0 reader. Each top-level Building becomes one object together with its
// BuildingPart children. Heights come from the geometry itself: an occluder spans the part's
// ground footprint up to the lowest point of its roof (thesis 7.1: occluders must lie inside the
// building, so a gabled roof contributes its eaves, not its ridge).
#include <cmath>
#include <unordered_map>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/InputError.hpp"
#include "urbanpvs/geometry/PolygonUnion.hpp"
#include "urbanpvs/geometry/RingCleanup.hpp"

namespace urbanpvs::geometry::detail {
namespace {

using Vertex = std::array<double, 3>;

// A part whose bottom floats this far (m) above its building's lowest point is raised (a bridge,
// an upper storey on columns): the space below it is open, so it yields no ground-based occluder.
constexpr double kRaisedPart = 1.0;
// Non-vertical faces whose projection is smaller than this (m²) add nothing to a footprint.
constexpr double kMinProjectedArea = 1e-4;

struct Surface {
  const Json* rings = nullptr;  // [[i, j, k, ...], [hole], ...]
  std::string semantic;         // "" when the file has no semantics for it
};

class CityJsonFile {
 public:
  CityJsonFile(const Json& doc, const std::string& file, const LocalFrameMapping* mapping)
      : doc_(doc), file_(file) {
    check_version();
    read_transform();
    if (mapping) convert_vertices(*mapping);
  }

  Box2 input_bounds() const {
    Box2 b;
    const Json& vs = vertices_json();
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const Vertex v = input_vertex(vs[i], i);
      b.extend(Vec2{v[0], v[1]});
    }
    return b;
  }

  const Json& objects() const {
    if (!doc_.contains("CityObjects") || !doc_["CityObjects"].is_object())
      throw InputError(InputProblem::BadStructure, file_, "", "no \"CityObjects\" object");
    return doc_["CityObjects"];
  }

  const Vertex& vertex(const Json& index, const std::string& feature) const {
    if (!index.is_number_unsigned() || index.get<std::size_t>() >= local_.size())
      throw InputError(InputProblem::BadStructure, file_, feature,
                       "vertex index " + index.dump() + " out of range (" +
                           std::to_string(local_.size()) + " vertices)");
    return local_[index.get<std::size_t>()];
  }

  const std::string& file() const { return file_; }

 private:
  void check_version() const {
    const std::string v =
        doc_.contains("version") && doc_["version"].is_string() ? doc_["version"].get<std::string>()
                                                                : "";
    if (v != "1.0" && v != "1.1" && v != "2.0")
      throw InputError(InputProblem::UnsupportedFormat, file_, "",
                       "CityJSON version \"" + v + "\" (supported: 1.0, 1.1, 2.0)");
  }

  void read_transform() {
    if (!doc_.contains("transform")) return;
    const Json& t = doc_["transform"];
    if (!t.is_object() || !t.contains("scale") || !t.contains("translate") ||
        !t["scale"].is_array() || !t["translate"].is_array() || t["scale"].size() != 3 ||
        t["translate"].size() != 3)
      throw InputError(InputProblem::BadStructure, file_, "transform",
                       "needs \"scale\" and \"translate\" with 3 numbers each");
    for (int i = 0; i < 3; ++i) {
      scale_[i] = json_number(t["scale"][i], file_, "transform", "scale");
      translate_[i] = json_number(t["translate"][i], file_, "transform", "translate");
    }
  }

  const Json& vertices_json() const {
    if (!doc_.contains("vertices") || !doc_["vertices"].is_array())
      throw InputError(InputProblem::BadStructure, file_, "", "no \"vertices\" array");
    return doc_["vertices"];
  }

  Vertex input_vertex(const Json& v, std::size_t i) const {
    const std::string what = "vertex " + std::to_string(i);
    if (!v.is_array() || v.size() != 3)
      throw InputError(InputProblem::BadStructure, file_, what, "is not [x, y, z]");
    Vertex out;
    for (int k = 0; k < 3; ++k)
      out[k] = json_number(v[k], file_, what, "coordinate") * scale_[k] + translate_[k];
    return out;
  }

  void convert_vertices(const LocalFrameMapping& mapping) {
    const Json& vs = vertices_json();
    local_.reserve(vs.size());
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const Vertex v = input_vertex(vs[i], i);
      local_.push_back(mapping.to_local(v[0], v[1], v[2]));
    }
  }

  const Json& doc_;
  const std::string& file_;
  std::array<double, 3> scale_{1, 1, 1};
  std::array<double, 3> translate_{0, 0, 0};
  std::vector<Vertex> local_;
};

bool is_array(const Json& j) { return j.is_array(); }

void malformed(const std::string& file, const std::string& id, const std::string& what) {
  throw InputError(InputProblem::BadStructure, file, id, what);
}

// Collects the surfaces of one geometry, with their semantic surface types where given.
std::vector<Surface> surfaces_of(const Json& g, const std::string& file, const std::string& id) {
  const std::string type = string_member(g, "type");
  if (!g.contains("boundaries")) malformed(file, id, type + " geometry without \"boundaries\"");
  const Json& b = g["boundaries"];
  if (!is_array(b)) malformed(file, id, type + " geometry without \"boundaries\" array");
  const Json* sem_surfaces = nullptr;
  const Json* sem_values = nullptr;
  if (g.contains("semantics") && g["semantics"].is_object()) {
    const Json& s = g["semantics"];
    if (s.contains("surfaces") && s["surfaces"].is_array()) sem_surfaces = &s["surfaces"];
    if (s.contains("values")) sem_values = &s["values"];
  }
  auto semantic_at = [&](const Json* values) -> std::string {
    if (!sem_surfaces || !values || !values->is_number_unsigned()) return {};
    const std::size_t k = values->get<std::size_t>();
    if (k >= sem_surfaces->size() || !(*sem_surfaces)[k].is_object()) return {};
    return string_member((*sem_surfaces)[k], "type");
  };
  auto child = [](const Json* v, std::size_t i) -> const Json* {
    return v && v->is_array() && i < v->size() ? &(*v)[i] : nullptr;
  };

  std::vector<Surface> out;
  // depth = nesting levels above the surface level: 0 surfaces, 1 shells, 2 solids.
  auto add_surfaces = [&](const Json& list, const Json* values) {
    if (!is_array(list)) malformed(file, id, "malformed " + type + " boundaries");
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (!is_array(list[i]) || list[i].empty() || !is_array(list[i][0]))
        malformed(file, id, "malformed " + type + " surface");
      out.push_back({&list[i], semantic_at(child(values, i))});
    }
  };
  if (type == "MultiSurface" || type == "CompositeSurface") {
    add_surfaces(b, sem_values);
  } else if (type == "Solid") {
    // Only the outer shell: inner shells are voids inside the building.
    if (!b.empty()) add_surfaces(b[0], child(sem_values, 0));
  } else if (type == "MultiSolid" || type == "CompositeSolid") {
    for (std::size_t s = 0; s < b.size(); ++s) {
      if (!is_array(b[s]) || b[s].empty()) malformed(file, id, "malformed " + type + " solid");
      add_surfaces(b[s][0], child(child(sem_values, s), 0));
    }
  }
  return out;
}

bool supported_geometry(const Json& g) {
  const std::string t = g.is_object() ? string_member(g, "type") : "";
  return t == "Solid" || t == "MultiSolid" || t == "CompositeSolid" || t == "MultiSurface" ||
         t == "CompositeSurface";
}

double lod_of(const Json& g) {
  if (!g.contains("lod")) return 0;
  const Json& l = g["lod"];
  if (l.is_number()) return l.get<double>();
  if (l.is_string()) {
    try {
      return std::stod(l.get<std::string>());
    } catch (...) {
      return 0;
    }
  }
  return 0;
}

// The geometry a building part is read from: the finest LoD below 3 (LoD3 adds balconies and
// overhangs that make footprints ambiguous), else the finest available.
const Json* chosen_geometry(const Json& obj) {
  if (!obj.contains("geometry") || !obj["geometry"].is_array()) return nullptr;
  const Json* best = nullptr;
  double best_key = -1e9;
  for (const Json& g : obj["geometry"]) {
    if (!supported_geometry(g)) continue;
    const double lod = lod_of(g);
    const double key = lod < 3 ? lod + 100 : -lod;
    if (key > best_key) best = &g, best_key = key;
  }
  return best;
}

struct Classified {
  std::vector<std::vector<Vertex>> rings;  // 3D rings of one surface
  enum Kind { Ground, Roof, Wall, Floor, Other } kind = Other;
};

std::vector<Vertex> ring_vertices(const CityJsonFile& f, const Json& ring, const std::string& id) {
  if (!is_array(ring)) malformed(f.file(), id, "ring is not an array of vertex indices");
  std::vector<Vertex> r;
  r.reserve(ring.size());
  for (const Json& i : ring) r.push_back(f.vertex(i, id));
  return r;
}

std::array<double, 3> newell_normal(const std::vector<Vertex>& r) {
  std::array<double, 3> n{0, 0, 0};
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vertex& a = r[i];
    const Vertex& b = r[(i + 1) % r.size()];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

Classified::Kind classify(const std::string& semantic, const std::vector<Vertex>& outer,
                          double part_zmin) {
  if (semantic == "GroundSurface") return Classified::Ground;
  if (semantic == "RoofSurface") return Classified::Roof;
  if (semantic == "WallSurface" || semantic == "ClosureSurface") return Classified::Wall;
  if (semantic == "OuterFloorSurface") return Classified::Floor;
  if (!semantic.empty()) return Classified::Other;
  // No semantics: decide by shape and position, not by the normal's sign, which files get wrong.
  const auto n = newell_normal(outer);
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (len == 0 || std::abs(n[2]) < 0.05 * len) return Classified::Wall;
  double zmax = -1e300;
  for (const Vertex& v : outer) zmax = std::max(zmax, v[2]);
  if (std::abs(n[2]) > 0.999 * len && zmax <= part_zmin + 0.05) return Classified::Ground;
  return Classified::Roof;
}

Polygon projected(const std::vector<std::vector<Vertex>>& rings) {
  Polygon p;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    Ring r;
    for (const Vertex& v : rings[i]) r.push_back({v[0], v[1]});
    if (i == 0)
      p.outer = std::move(r);
    else
      p.holes.push_back(std::move(r));
  }
  return p;
}

// Projects surfaces to the ground plane as valid polygons, leaving out slivers (near-vertical
// faces) that have no area in plan.
std::vector<Polygon> plan_polygons(const std::vector<const Classified*>& faces,
                                   const std::string& file, const std::string& id,
                                   ReadReport& report) {
  std::vector<Polygon> out;
  for (const Classified* c : faces) {
    Polygon p = projected(c->rings);
    if (std::abs(signed_area2(p.outer)) * 0.5 < kMinProjectedArea) continue;
    std::vector<Ring> rings{std::move(p.outer)};
    for (Ring& h : p.holes)
      if (std::abs(signed_area2(h)) * 0.5 >= kMinProjectedArea) rings.push_back(std::move(h));
    out.push_back(clean_polygon(std::move(rings), {file, id, false}, report));
  }
  return out;
}

struct PartResult {
  std::vector<Polygon> footprint;
  double zmin = 0, top = 0;
  bool raised_candidate = false;  // has a bottom face, so it may float above its building
  Box3 box;
};

PartResult read_part(const CityJsonFile& f, const Json& obj, const std::string& id,
                     ReadReport& report) {
  PartResult out;
  const Json* g = chosen_geometry(obj);
  if (!g) return out;
  std::vector<Classified> faces;
  std::vector<std::string> semantics;
  for (const Surface& s : surfaces_of(*g, f.file(), id)) {
    Classified c;
    for (const Json& ring : *s.rings) c.rings.push_back(ring_vertices(f, ring, id));
    for (const auto& r : c.rings)
      for (const Vertex& v : r) out.box.extend(Vec2{v[0], v[1]}, v[2]);
    faces.push_back(std::move(c));
    semantics.push_back(s.semantic);
  }
  if (faces.empty()) return out;
  out.zmin = out.box.zmin;
  std::vector<const Classified*> ground, roof;
  double roof_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < faces.size(); ++i) {
    faces[i].kind = classify(semantics[i], faces[i].rings.front(), out.zmin);
    if (faces[i].kind == Classified::Ground) ground.push_back(&faces[i]);
    if (faces[i].kind == Classified::Roof) {
      roof.push_back(&faces[i]);
      for (const Vertex& v : faces[i].rings.front()) roof_min = std::min(roof_min, v[2]);
    }
    if (faces[i].kind == Classified::Floor || faces[i].kind == Classified::Ground)
      out.raised_candidate = true;
  }
  out.top = roof.empty() ? out.box.zmax : roof_min;
  std::vector<Polygon> plan = plan_polygons(ground, f.file(), id, report);
  if (plan.empty()) {
    plan = plan_polygons(roof, f.file(), id, report);
    if (!plan.empty()) ++report.footprints_from_roof;
  }
  out.footprint = plan.size() > 1 ? union_polygons(plan) : std::move(plan);
  return out;
}

struct Objects {
  const CityJsonFile& file;
  std::unordered_map<std::string, const Json*> by_id;
  ReadReport& report;

  const Json* find(const std::string& id) const {
    auto it = by_id.find(id);
    return it == by_id.end() ? nullptr : it->second;
  }

  bool has_known_parent(const Json& obj) const {
    if (!obj.contains("parents") || !obj["parents"].is_array()) return false;
    for (const Json& p : obj["parents"])
      if (p.is_string() && find(p.get<std::string>())) return true;
    return false;
  }

  // The object itself and its BuildingPart descendants, depth first in file order.
  void collect_parts(const std::string& id, const Json& obj,
                     std::vector<std::pair<std::string, const Json*>>& out, int depth) const {
    if (depth > 32) malformed(file.file(), id, "BuildingPart nesting deeper than 32 (a cycle?)");
    out.emplace_back(id, &obj);
    if (!obj.contains("children") || !obj["children"].is_array()) return;
    for (const Json& c : obj["children"]) {
      if (!c.is_string()) continue;
      const Json* child = find(c.get<std::string>());
      if (!child) continue;
      if (!child->is_object()) malformed(file.file(), c.get<std::string>(), "city object is not a JSON object");
      if (string_member(*child, "type") == "BuildingPart")
        collect_parts(c.get<std::string>(), *child, out, depth + 1);
    }
  }
};

CityObject read_building(const Objects& objs, const std::string& id, const Json& obj) {
  std::vector<std::pair<std::string, const Json*>> members;
  objs.collect_parts(id, obj, members, 0);
  CityObject o;
  o.source_id = id;
  std::vector<PartResult> parts;
  for (const auto& [pid, pobj] : members) {
    PartResult r = read_part(objs.file, *pobj, pid, objs.report);
    if (!r.box.xy.empty()) {
      o.bbox.extend(r.box);
      parts.push_back(std::move(r));
    }
  }
  if (parts.empty()) return o;
  o.ground_z = o.bbox.zmin;
  std::vector<Polygon> ground_parts;
  for (PartResult& r : parts) {
    const bool raised = r.raised_candidate && r.zmin > o.ground_z + kRaisedPart;
    if (raised) continue;
    for (Polygon& p : r.footprint) {
      o.occluders.push_back({p, r.zmin, r.top});
      ground_parts.push_back(std::move(p));
    }
  }
  o.footprint = ground_parts.size() > 1 ? union_polygons(ground_parts) : std::move(ground_parts);
  return o;
}

void read_terrain(const CityJsonFile& f, const std::string& id, const Json& obj, Terrain& t) {
  const Json* g = chosen_geometry(obj);
  if (!g) return;
  for (const Surface& s : surfaces_of(*g, f.file(), id)) {
    const std::vector<Vertex> r = ring_vertices(f, (*s.rings)[0], id);
    for (std::size_t i = 1; i + 1 < r.size(); ++i) t.triangles.push_back({{r[0], r[i], r[i + 1]}});
  }
}

}  // namespace

InputScan scan_cityjson(const Json& doc, const std::string& file) {
  CityJsonFile f(doc, file, nullptr);
  InputScan scan;
  scan.bounds = f.input_bounds();
  std::string rs;
  if (doc.contains("metadata") && doc["metadata"].is_object() &&
      doc["metadata"].contains("referenceSystem") && doc["metadata"]["referenceSystem"].is_string())
    rs = doc["metadata"]["referenceSystem"].get<std::string>();
  if (rs.empty()) {
    scan.note = file + ": no referenceSystem; coordinates taken as projected metres";
  } else {
    scan.crs = normalise_crs(rs, file);
    scan.note = file + ": reference system " + scan.crs;
  }
  scan.kind = is_geographic_crs(scan.crs) ? LocalFrame::Kind::Geographic
                                          : LocalFrame::Kind::Projected;
  return scan;
}

void load_cityjson(const Json& doc, const std::string& file, const LocalFrameMapping& mapping,
                   const ReadOptions& options, City& city) {
  CityJsonFile f(doc, file, &mapping);
  const Json& all = f.objects();
  Objects objs{f, {}, city.report};
  for (auto it = all.begin(); it != all.end(); ++it) objs.by_id.emplace(it.key(), &it.value());

  for (auto it = all.begin(); it != all.end(); ++it) {
    const std::string& id = it.key();
    const Json& obj = it.value();
    if (!obj.is_object()) malformed(file, id, "city object is not a JSON object");
    if (!obj.contains("type") || !obj["type"].is_string())
      malformed(file, id, "city object has no \"type\" string");
    const std::string type = string_member(obj, "type");
    if (type == "TINRelief") {
      read_terrain(f, id, obj, city.terrain);
      continue;
    }
    const bool building = type == "Building" || type == "BuildingPart";
    if (!building) {
      ++city.report.ignored_types[type.empty() ? "(no type)" : type];
      continue;
    }
    if (objs.has_known_parent(obj)) continue;  // read with its parent
    if (type == "BuildingPart")
      city.report.warnings.push_back(file + ": " + id + ": BuildingPart without a known parent "
                                     "read as a building of its own");
    try {
      CityObject o = read_building(objs, id, obj);
      if (o.bbox.xy.empty()) {
        city.report.warnings.push_back(file + ": " + id + ": building without usable geometry "
                                       "(no LoD1/LoD2 solid or surface) skipped");
        continue;
      }
      city.objects.push_back(std::move(o));
    } catch (const InputError& e) {
      if (!options.skip_invalid || e.problem() != InputProblem::InvalidGeometry) throw;
      ++city.report.skipped_invalid;
      city.report.warnings.push_back(std::string(e.what()) + " (skipped)");
    }
  }
}

}  // namespace urbanpvs::geometry::detail
