// SPDX-License-Identifier: GPL-3.0-or-later
// CityJSON 1.0/1.1/2.0 reader. Each top-level Building becomes one object together with its
// BuildingPart children and its installations. Heights come from the geometry itself: an
// occluder spans the part's ground footprint up to the lowest point of every surface it shows
// upward (thesis 7.1: occluders must lie inside the building, so a gabled roof contributes its
// eaves, not its ridge, and a terrace its floor). Parts off the ground, and installations, give
// no occluder; a footprint from a roof's projection is used only where walls stand under it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/ObjectOutline.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/city/RoofPrisms.hpp"
#include "urbanpvs/geometry/city/SteppedRoof.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry::detail {
namespace {

using Vertex = Vec3;

// A part whose bottom floats this far (m) above its building's lowest point is raised (a bridge,
// an upper storey on columns): the space below it is open, so it yields no ground-based occluder.
constexpr double kRaisedPart = 1.0;
// Non-vertical faces whose projection is smaller than this (m²) add nothing to a footprint.
constexpr double kMinProjectedArea = 1e-4;
// The largest coordinate (m, or degrees) a vertex may have after its transform (input_vertex).
constexpr double kFarthestCoordinate = 1e8;

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
  void check_version() {
    const std::string v = doc_.contains("version") && doc_["version"].is_string()
                              ? doc_["version"].get<std::string>()
                              : "";
    if (v != "1.0" && v != "1.1" && v != "2.0")
      throw InputError(InputProblem::UnsupportedFormat, file_, "",
                       "CityJSON version \"" + v + "\" (supported: 1.0, 1.1, 2.0)");
    version_ = v;
  }

  void read_transform() {
    if (!doc_.contains("transform")) {
      // CityJSON 1.1 and 2.0 store integer vertices that only mean something with their
      // transform; reading them as metres would give a city a thousand times too large.
      if (version_ != "1.0")
        throw InputError(InputProblem::BadStructure, file_, "transform",
                         "CityJSON " + version_ + " requires \"transform\" (none given)");
      return;
    }
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
    for (int k = 0; k < 3; ++k) {
      out[k] = json_number(v[k], file_, what, "coordinate") * scale_[k] + translate_[k];
      // No reference system puts a place on Earth 1e8 m from its origin (its circumference is
      // 4e7 m; zone-prefixed eastings stay under 1e8). A vertex beyond that is a broken
      // transform or an integer past any precision: in the local frame every such vertex
      // would round to the same point, and the city would silently collapse.
      if (!(std::abs(out[k]) <= kFarthestCoordinate)) {
        char where[160];
        std::snprintf(where, sizeof where,
                      "coordinate %.6g (after the transform) is farther than %.0g from its "
                      "reference system's origin",
                      out[k], kFarthestCoordinate);
        throw InputError(InputProblem::Implausible, file_, what, where);
      }
    }
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
  std::string version_;
  std::array<double, 3> scale_{1, 1, 1};
  std::array<double, 3> translate_{0, 0, 0};
  std::vector<Vertex> local_;
};

bool is_array(const Json& j) {
  return j.is_array();
}

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
      // A surface without rings (`[]`, as some converters write a face they dropped) has no
      // area: nothing to read and nothing lost, so it is passed over, not the city refused.
      if (is_array(list[i]) && list[i].empty()) continue;
      if (!is_array(list[i]) || !is_array(list[i][0]))
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
  // Top: a surface the building shows upward (roof, terrace); its lowest point bounds the
  // occluder's top. Ceiling: an OuterCeilingSurface, facing down (arcade, pilotis, skyway).
  enum Kind { Ground, Top, Wall, Ceiling, Other } kind = Other;
};

std::vector<Vertex> ring_vertices(const CityJsonFile& f, const Json& ring, const std::string& id) {
  if (!is_array(ring)) malformed(f.file(), id, "ring is not an array of vertex indices");
  std::vector<Vertex> r;
  r.reserve(ring.size());
  for (const Json& i : ring) r.push_back(f.vertex(i, id));
  return r;
}

Vec3 newell_normal(const std::vector<Vertex>& r) {
  Vec3 n{0, 0, 0};
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vertex& a = r[i];
    const Vertex& b = r[(i + 1) % r.size()];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

bool is_vertical(const std::vector<Vertex>& outer) {
  const auto n = newell_normal(outer);
  const double len = glm::length(n);
  return len == 0 || std::abs(n[2]) < 0.05 * len;
}

// Semantic surface types of CityJSON 1.1/2.0 that are no top of an occluder although they may
// face up: interior surfaces (their floors lie inside the building, at any storey), openings
// (a roof window lies in its roof), and the surfaces of water and transport objects.
bool known_non_top(const std::string& s) {
  static constexpr std::array<std::string_view, 12> kTypes{"InteriorWallSurface",
                                                           "FloorSurface",
                                                           "CeilingSurface",
                                                           "Door",
                                                           "Window",
                                                           "WaterSurface",
                                                           "WaterGroundSurface",
                                                           "WaterClosureSurface",
                                                           "TrafficArea",
                                                           "AuxiliaryTrafficArea",
                                                           "TransportationMarking",
                                                           "TransportationHole"};
  return std::find(kTypes.begin(), kTypes.end(), s) != kTypes.end();
}

Classified::Kind classify(const std::string& semantic, const std::vector<Vertex>& outer,
                          double part_zmin) {
  if (semantic == "GroundSurface") return Classified::Ground;
  // Thesis 7.1: the occluder must stay inside the building, so it ends at the lowest point of
  // every surface the building shows upward: roofs, terraces (OuterFloorSurface), and any type
  // we do not know (extensions such as "+Terrace") unless it is vertical. A surface we cannot
  // place is not assumed to lie above the occluder.
  if (semantic == "RoofSurface" || semantic == "OuterFloorSurface") return Classified::Top;
  if (semantic == "WallSurface" || semantic == "ClosureSurface") return Classified::Wall;
  if (semantic == "OuterCeilingSurface") return Classified::Ceiling;
  if (known_non_top(semantic)) return Classified::Other;
  if (!semantic.empty()) return is_vertical(outer) ? Classified::Other : Classified::Top;
  // No semantics: decide by shape and position, not by the normal's sign, which files get wrong.
  const auto n = newell_normal(outer);
  const double len = glm::length(n);
  if (len == 0 || std::abs(n[2]) < 0.05 * len) return Classified::Wall;
  double zmax = -1e300;
  for (const Vertex& v : outer) zmax = std::max(zmax, v[2]);
  if (std::abs(n[2]) > 0.999 * len && zmax <= part_zmin + 0.05) return Classified::Ground;
  return Classified::Top;
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
                                   const ReadOptions& options, ReadReport& report) {
  std::vector<Polygon> out;
  for (const Classified* c : faces) {
    Polygon p = projected(c->rings);
    if (std::abs(signed_area2(p.outer)) * 0.5 < kMinProjectedArea) continue;
    std::vector<Ring> rings{std::move(p.outer)};
    for (Ring& h : p.holes)
      if (std::abs(signed_area2(h)) * 0.5 >= kMinProjectedArea) rings.push_back(std::move(h));
    for (Polygon& q : clean_polygon(std::move(rings), {file, id, false, options.strict}, report))
      out.push_back(std::move(q));
  }
  return out.size() > 1 ? union_polygons(out) : out;
}

struct PartResult {
  std::string id;
  std::vector<Classified> faces;
  std::vector<Surface3> surfaces;
  std::vector<Polygon> ground_plan;  // projection of its GroundSurfaces
  double zmin = 0, top = 0;
  bool has_ground = false;      // a GroundSurface (or, without semantics, a flat bottom face)
  bool has_ceiling = false;     // an OuterCeilingSurface
  bool height_unknown = false;  // only a LoD0 footprint: where its top is, the file says not
  Box3 box;

  std::vector<const Classified*> of_kind(Classified::Kind k) const {
    std::vector<const Classified*> out;
    for (const Classified& c : faces)
      if (c.kind == k) out.push_back(&c);
    return out;
  }
};

PartResult read_part(const CityJsonFile& f, const Json& obj, const std::string& id,
                     const ReadOptions& options, ReadReport& report) {
  PartResult out;
  out.id = id;
  const Json* g = chosen_geometry(obj);
  if (!g) return out;
  out.height_unknown = lod_of(*g) < 1;
  std::vector<std::string> semantics;
  for (const Surface& s : surfaces_of(*g, f.file(), id)) {
    Classified c;
    for (const Json& ring : *s.rings) c.rings.push_back(ring_vertices(f, ring, id));
    for (const auto& r : c.rings)
      for (const Vertex& v : r) out.box.extend(Vec2{v[0], v[1]}, v[2]);
    out.surfaces.push_back({c.rings});
    out.faces.push_back(std::move(c));
    semantics.push_back(s.semantic);
  }
  if (out.faces.empty()) return out;
  out.zmin = out.box.zmin;
  double top_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < out.faces.size(); ++i) {
    Classified& c = out.faces[i];
    c.kind = classify(semantics[i], c.rings.front(), out.zmin);
    out.has_ground = out.has_ground || c.kind == Classified::Ground;
    out.has_ceiling = out.has_ceiling || c.kind == Classified::Ceiling;
    if (c.kind == Classified::Top)
      for (const auto& r : c.rings)
        for (const Vertex& v : r) top_min = std::min(top_min, v[2]);
  }
  out.top = std::isfinite(top_min) ? top_min : out.box.zmax;
  if (out.has_ground)
    out.ground_plan = plan_polygons(out.of_kind(Classified::Ground), f.file(), id, options, report);
  return out;
}

// ---- footprints of parts without GroundSurface ----
//
// Such a part's footprint would be the projection of its upward surfaces, but a roof that
// overhangs its walls projects beyond the building: a prism over it stands in open air under
// the eaves (thesis 7.1). So the projection is used only where walls stand under every edge of
// it; else the footprint is the outline of the walls' bottom edges; else the part gives no
// occluder.

// Tolerance (m) for a wall to stand under a roof edge and for a wall outline to lie under the
// roof: rounding of stored coordinates, far below the occluder shrinking that follows.
constexpr double kWallTolerance = 0.02;
// How far (m) walls may stand from a GroundSurface's edge and still hold it up. Producers often
// draw the ground apart from the walls (Zürich's LoD2: a notch of 0.7 m cut straight across);
// the ground test is after walls that are not there at all (an XLink to a missing wall, a
// hole in the ground under a roof that closes over it). A ground drawn up to this far beyond its
// walls is left to the occluder shrinking by ε downstream (1 m by default, thesis 7.2), as
// before the test.
constexpr double kGroundWallReach = 1.0;

// A vertical wall in plan: the thin rectangle t in [t0, t1] along d, s in [s0, s1] along n.
struct WallPlan {
  Vec2 d, n;
  double t0, t1, s0, s1;
};

std::optional<WallPlan> wall_plan(const Classified& c) {
  const auto n3 = newell_normal(c.rings.front());
  const double h = std::hypot(n3[0], n3[1]);
  if (h == 0) return std::nullopt;
  WallPlan w{{-n3[1] / h, n3[0] / h}, {n3[0] / h, n3[1] / h}, 1e300, -1e300, 1e300, -1e300};
  for (const Vertex& v : c.rings.front()) {
    const Vec2 p{v[0], v[1]};
    w.t0 = std::min(w.t0, dot(p, w.d)), w.t1 = std::max(w.t1, dot(p, w.d));
    w.s0 = std::min(w.s0, dot(p, w.n)), w.s1 = std::max(w.s1, dot(p, w.n));
  }
  // A leaning wall's foot is not under its top: it vouches for no roof edge.
  if (w.s1 - w.s0 > kWallTolerance) return std::nullopt;
  return w;
}

// True when walls stand under the whole segment ab (within `tolerance`).
bool on_walls(Vec2 a, Vec2 b, const std::vector<WallPlan>& walls, double tolerance) {
  const Vec2 ab = b - a;
  const double len = std::hypot(ab.x, ab.y);
  if (len <= tolerance) return true;
  std::vector<std::pair<double, double>> covered;
  for (const WallPlan& w : walls) {
    double lo = 0, hi = 1;
    for (const auto& [axis, m0, m1] : {std::tuple{w.d, w.t0, w.t1}, std::tuple{w.n, w.s0, w.s1}}) {
      const double pa = dot(a, axis), dp = dot(ab, axis);
      const double q0 = m0 - tolerance, q1 = m1 + tolerance;
      if (std::abs(dp) < 1e-12) {
        if (pa < q0 || pa > q1) hi = -1;
        continue;
      }
      double u0 = (q0 - pa) / dp, u1 = (q1 - pa) / dp;
      if (u0 > u1) std::swap(u0, u1);
      lo = std::max(lo, u0), hi = std::min(hi, u1);
    }
    if (hi > lo) covered.emplace_back(lo, hi);
  }
  std::sort(covered.begin(), covered.end());
  const double gap = tolerance / len;
  double reach = 0;
  for (const auto& [lo, hi] : covered) {
    if (lo > reach + gap) break;
    reach = std::max(reach, hi);
  }
  return reach >= 1 - gap;
}

bool outline_on_walls(const std::vector<Polygon>& plan, const std::vector<WallPlan>& walls,
                      double tolerance = kWallTolerance) {
  bool ok = true;
  for (const Polygon& p : plan)
    for_each_edge(p, [&](Vec2 a, Vec2 b) { ok = ok && on_walls(a, b, walls, tolerance); });
  return ok;
}

// The outline of the part's walls at their feet: the bottom edges (the wall lies above them)
// that no other surface of the part shares (a step wall shares its foot with the lower roof, a
// triangulated wall its diagonals), chained into closed rings. Empty when they do not close
// into simple rings.
std::vector<Polygon> wall_outline(const PartResult& part) {
  using Key = std::array<double, 6>;
  auto key = [](const Vertex& a, const Vertex& b) {
    return lexicographic_less(a, b) ? Key{a[0], a[1], a[2], b[0], b[1], b[2]}
                                    : Key{b[0], b[1], b[2], a[0], a[1], a[2]};
  };
  std::map<Key, int> uses;
  for (const Classified& c : part.faces)
    for (const auto& r : c.rings)
      for (std::size_t i = 0; i < r.size(); ++i) ++uses[key(r[i], r[(i + 1) % r.size()])];
  std::vector<std::pair<Vec2, Vec2>> feet;
  for (const Classified* c : part.of_kind(Classified::Wall)) {
    const auto& r = c->rings.front();  // holes are openings: their top edges are no feet
    const auto n = newell_normal(r);
    const double nlen = glm::length(n);
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Vertex &a = r[i], &b = r[(i + 1) % r.size()];
      const Vec3 e = b - a;
      // n x e points into the face: up for an edge the wall stands on.
      const double inward_z = n[0] * e[1] - n[1] * e[0];
      if (inward_z <= 0.3 * nlen * glm::length(e) || uses[key(a, b)] != 1) continue;
      const Vec2 p{a[0], a[1]}, q{b[0], b[1]};
      if (!(p == q)) feet.emplace_back(p, q);
    }
  }
  // Chain: every point must join exactly two feet.
  std::map<std::pair<double, double>, std::vector<std::size_t>> at;
  for (std::size_t i = 0; i < feet.size(); ++i) {
    at[{feet[i].first.x, feet[i].first.y}].push_back(i);
    at[{feet[i].second.x, feet[i].second.y}].push_back(i);
  }
  for (const auto& [p, segments] : at)
    if (segments.size() != 2) return {};
  std::vector<bool> used(feet.size(), false);
  std::vector<Ring> rings;
  for (std::size_t s = 0; s < feet.size(); ++s) {
    if (used[s]) continue;
    Ring ring{feet[s].first};
    Vec2 cur = feet[s].second;
    std::size_t seg = s;
    used[s] = true;
    while (!(cur == ring.front())) {
      ring.push_back(cur);
      const auto& pair = at[{cur.x, cur.y}];
      seg = pair[0] == seg ? pair[1] : pair[0];
      if (used[seg]) return {};
      used[seg] = true;
      cur = feet[seg].first == cur ? feet[seg].second : feet[seg].first;
    }
    if (ring.size() < 3) return {};
    rings.push_back(std::move(ring));
  }
  // Nesting depth decides outer ring or hole; a hole joins the smallest ring around it.
  std::vector<std::size_t> depth(rings.size(), 0);
  for (std::size_t i = 0; i < rings.size(); ++i)
    for (std::size_t j = 0; j < rings.size(); ++j)
      if (i != j && inside_ring(rings[j], rings[i].front())) ++depth[i];
  std::vector<Polygon> out;
  std::vector<std::size_t> outer_ring;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    if (depth[i] % 2) continue;
    if (signed_area2(rings[i]) < 0) std::reverse(rings[i].begin(), rings[i].end());
    out.push_back({rings[i], {}});
    outer_ring.push_back(i);
  }
  for (std::size_t i = 0; i < rings.size(); ++i) {
    if (depth[i] % 2 == 0) continue;
    std::size_t best = out.size();
    for (std::size_t k = 0; k < out.size(); ++k)
      if (depth[outer_ring[k]] + 1 == depth[i] && inside_ring(out[k].outer, rings[i].front()) &&
          (best == out.size() ||
           std::abs(signed_area2(out[k].outer)) < std::abs(signed_area2(out[best].outer))))
        best = k;
    if (best == out.size()) return {};
    if (signed_area2(rings[i]) > 0) std::reverse(rings[i].begin(), rings[i].end());
    out[best].holes.push_back(rings[i]);
  }
  for (const Polygon& p : out)
    if (!polygon_defect(p).empty() || area(p) < kMinProjectedArea) return {};
  return out;
}

// True when every vertex of `inner` lies in `outer` or within kWallTolerance of its boundary.
bool within(const std::vector<Polygon>& inner, const std::vector<Polygon>& outer) {
  auto covered = [&](Vec2 q) {
    for (const Polygon& p : outer) {
      if (inside(p, q)) return true;
      bool near = false;
      for_each_edge(p, [&](Vec2 a, Vec2 b) {
        near = near || distance_to_segment(q, a, b) <= kWallTolerance;
      });
      if (near) return true;
    }
    return false;
  };
  bool ok = true;
  for (const Polygon& p : inner) for_each_edge(p, [&](Vec2 a, Vec2) { ok = ok && covered(a); });
  return ok;
}

struct GroundlessFootprint {
  std::vector<Polygon> occluder;   // where the part certainly stands: empty if unknown
  std::vector<Polygon> footprint;  // its plan for o.footprint (what no view cell may enter)
};

GroundlessFootprint groundless_footprint(const PartResult& part, const std::vector<WallPlan>& walls,
                                         const std::string& file, const ReadOptions& options,
                                         ReadReport& report) {
  GroundlessFootprint out;
  out.footprint = plan_polygons(part.of_kind(Classified::Top), file, part.id, options, report);
  if (out.footprint.empty()) return out;
  if (outline_on_walls(out.footprint, walls)) {
    ++report.footprints_from_roof;
    out.occluder = out.footprint;
    return out;
  }
  if (std::vector<Polygon> feet = wall_outline(part);
      !feet.empty() && within(feet, out.footprint)) {
    ++report.footprints_from_walls;
    out.occluder = feet.size() > 1 ? union_polygons(feet) : std::move(feet);
    return out;
  }
  ++report.footprints_unknown;
  report.warnings.push_back(file + ": " + part.id +
                            ": no GroundSurface, its roof overhangs its walls and the walls give "
                            "no closed outline: no occluder for this part");
  return out;
}

// Every surface of the part that may bound it from above, for its stepped height field
// (SteppedRoof.hpp): roofs and terraces, and walls and ceilings that are not vertical (a
// leaning wall or an overhang's underside is met first by a vertical line under it). Interior
// and opening types do not count: they lie inside the building or in its roof. Their plans are
// cleaned without counting repairs: a face is not refused or repaired for how it projects.
std::vector<RoofFace> roof_faces(const PartResult& part, const std::string& file) {
  std::vector<RoofFace> out;
  ReadReport scratch;
  const ReadOptions lenient;
  for (const Classified& c : part.faces) {
    if (c.kind != Classified::Top && c.kind != Classified::Wall && c.kind != Classified::Ceiling)
      continue;
    std::vector<Polygon> plan = plan_polygons({&c}, file, part.id, lenient, scratch);
    if (!plan.empty()) out.push_back(roof_face(c.rings, std::move(plan)));
  }
  return out;
}

struct Objects {
  const CityJsonFile& file;
  std::unordered_map<std::string, const Json*> by_id;
  const ReadOptions& options;
  ReadReport& report;
  /// Building or BuildingPart id -> its installations and other non-part children.
  std::unordered_map<std::string, std::vector<std::string>> installations;

  const Json* find(const std::string& id) const {
    auto it = by_id.find(id);
    return it == by_id.end() ? nullptr : it->second;
  }

  // Whether the object `id` is read with another one: collect_parts reads the BuildingPart
  // children a Building or BuildingPart lists, down from the one read on its own. Any other
  // parent reads nothing of it (a CityObjectGroup, which CityJSON 2.0 members may name among
  // their "parents"; an extension's type; a parent that does not list it among its children;
  // a Building under a Building): such an object is read on its own, or it would be lost
  // without a word. Parents that list each other round a cycle all read on their own, and
  // collect_parts then refuses the cycle.
  bool read_with_parent(const std::string& id, const Json& obj) const {
    std::string at = id;
    const Json* node = &obj;
    for (int depth = 0; depth <= 32; ++depth) {
      const std::string up = collecting_parent(at, *node);
      if (up.empty()) return depth > 0;
      at = up;
      node = find(up);
    }
    return false;
  }

  // The Building or BuildingPart that `obj` (a BuildingPart) names among its parents and that
  // lists `id` among its children, or "".
  std::string collecting_parent(const std::string& id, const Json& obj) const {
    if (string_member(obj, "type") != "BuildingPart" || !obj.contains("parents") ||
        !obj["parents"].is_array())
      return {};
    for (const Json& p : obj["parents"]) {
      const Json* parent = p.is_string() ? find(p.get<std::string>()) : nullptr;
      if (!parent || !parent->is_object()) continue;
      const std::string type = string_member(*parent, "type");
      if (type != "Building" && type != "BuildingPart") continue;
      if (!parent->contains("children") || !(*parent)["children"].is_array()) continue;
      for (const Json& c : (*parent)["children"])
        if (c.is_string() && c.get<std::string>() == id) return p.get<std::string>();
    }
    return {};
  }

  // The Building or BuildingPart that `obj` (of another type) belongs to, or "".
  std::string building_parent(const Json& obj) const {
    if (!obj.contains("parents") || !obj["parents"].is_array()) return {};
    for (const Json& p : obj["parents"]) {
      const Json* parent = p.is_string() ? find(p.get<std::string>()) : nullptr;
      if (!parent) continue;
      const std::string type = string_member(*parent, "type");
      if (type == "Building" || type == "BuildingPart") return p.get<std::string>();
    }
    return {};
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
      if (!child->is_object())
        malformed(file.file(), c.get<std::string>(), "city object is not a JSON object");
      if (string_member(*child, "type") == "BuildingPart")
        collect_parts(c.get<std::string>(), *child, out, depth + 1);
    }
  }

  // Calls f(vertices of one surface) for every surface of the installations of `members`.
  template <class F>
  void for_each_installation_surface(
      const std::vector<std::pair<std::string, const Json*>>& members, F&& f) const {
    for (const auto& [pid, pobj] : members) {
      const auto it = installations.find(pid);
      if (it == installations.end()) continue;
      for (const std::string& iid : it->second) {
        const Json* g = chosen_geometry(*find(iid));
        if (!g) continue;
        for (const Surface& s : surfaces_of(*g, file.file(), iid)) {
          Surface3 sf;
          for (const Json& ring : *s.rings) sf.rings.push_back(ring_vertices(file, ring, iid));
          f(std::move(sf));
        }
      }
    }
  }
};

// Reads a Building with its parts and installations. `why_not` says why it occludes nothing
// when it cannot (o.occludes false).
CityObject read_building(const Objects& objs, const std::string& id, const Json& obj,
                         std::string& why_not) {
  std::vector<std::pair<std::string, const Json*>> members;
  objs.collect_parts(id, obj, members, 0);
  // A polygon the CityGML reader could not read: the rest cannot be trusted to bound an
  // occluder (a roof face missing would lift the top), so none is made (thesis 7.1).
  for (const auto& [pid, pobj] : members)
    if (pobj->contains(kUnreadableMember))
      throw InputError(InputProblem::InvalidGeometry, objs.file.file(), pid,
                       string_member(*pobj, kUnreadableMember));
  CityObject o;
  o.source_id = id;
  std::vector<PartResult> parts;
  for (std::uint32_t part = 0; part < members.size(); ++part) {
    const auto& [pid, pobj] = members[part];
    PartResult r = read_part(objs.file, *pobj, pid, objs.options, objs.report);
    if (!r.box.xy.empty()) {
      o.bbox.extend(r.box);
      for (Surface3& sf : r.surfaces) {
        sf.part = part;
        o.surfaces.push_back(std::move(sf));
      }
      r.surfaces.clear();
      parts.push_back(std::move(r));
    }
  }
  // Where the building stands: the lowest point of its parts (an installation, such as a stair
  // down to a basement, does not lift its parts off the ground).
  const double parts_zmin = o.bbox.zmin;
  // Installations belong to the building: they widen its box (it is tested for visibility
  // over all of it) and their surfaces are its own, but they give no occluder: balconies,
  // chimneys and dormers are no volume a prism from the ground may fill (thesis 7.1).
  objs.for_each_installation_surface(members, [&](Surface3 sf) {
    for (const auto& r : sf.rings)
      for (const Vertex& v : r) o.bbox.extend(Vec2{v[0], v[1]}, v[2]);
    sf.part = Surface3::kInstallation;
    o.surfaces.push_back(std::move(sf));
  });
  o.ground_z = o.bbox.zmin;
  if (parts.empty()) {
    if (!o.bbox.xy.empty()) {
      o.occludes = false;
      why_not = "only installations, no geometry of its own";
    }
    return o;
  }
  // A LoD0 footprint beside parts with solids (3D BAG: on the Building, its solids on the
  // BuildingPart) adds nothing; only LoD0 alone leaves the height unknown.
  const bool height_unknown =
      std::all_of(parts.begin(), parts.end(), [](const PartResult& r) { return r.height_unknown; });
  // Parts off the ground give no occluder: the occluders downstream are prisms standing on the
  // ground, and the space below such a part is open (thesis 7.1). Raised are parts whose
  // underside is an OuterCeilingSurface with no GroundSurface (arcades, pilotis, skyways), and
  // parts whose lowest point floats more than kRaisedPart above the building's, whether or not
  // they have a bottom (a bottomless dormer on a roof that overhangs the walls).
  std::vector<const PartResult*> standing;
  for (const PartResult& r : parts) {
    if (r.height_unknown && !height_unknown) continue;
    if ((r.has_ceiling && !r.has_ground) || r.zmin > parts_zmin + kRaisedPart) {
      ++objs.report.raised_parts;
      continue;
    }
    standing.push_back(&r);
  }
  std::vector<WallPlan> walls;  // of every standing part: parts meet at walls of either
  for (const PartResult* r : standing)
    for (const Classified* c : r->of_kind(Classified::Wall))
      if (std::optional<WallPlan> w = wall_plan(*c)) walls.push_back(*w);
  std::vector<Polygon> ground_parts;
  bool lost = false;       // a part on the ground left without footprint
  bool off_walls = false;  // a part whose ground plan no walls stand on
  for (const PartResult* r : standing) {
    std::vector<Polygon> occluder, footprint;
    if (r->has_ground) {
      footprint = r->ground_plan;
      // The prism over a ground plan stands for walls round it; where the file has none (an
      // XLink to a wall that is not there, a shell that is only a ground and a roof) the
      // validator's rays pass where the prism would block them: no occluder for the part. The
      // walls round its outer rings suffice. A hole needs none: a line into the prism through
      // a hole's edge starts in the hole, and the building's walls and roof round the hole
      // block it before it leaves (a courtyard under a roof that closes over it, drawn without
      // inner walls).
      std::vector<Polygon> outer_rings;
      for (const Polygon& p : r->ground_plan) outer_rings.push_back(Polygon{p.outer, {}});
      // (A LoD0 footprint has no walls to ask: its height is unknown, and it occludes nothing.)
      if (r->height_unknown || outline_on_walls(outer_rings, walls, kGroundWallReach)) {
        occluder = r->ground_plan;
      } else {
        ++objs.report.grounds_off_walls;
        off_walls = true;
        objs.report.warnings.push_back(objs.file.file() + ": " + r->id +
                                       ": walls do not stand round its GroundSurface: no "
                                       "occluder for this part");
      }
    } else {
      GroundlessFootprint g =
          groundless_footprint(*r, walls, objs.file.file(), objs.options, objs.report);
      occluder = std::move(g.occluder);
      footprint = std::move(g.footprint);
    }
    lost = lost || footprint.empty();
    std::vector<RoofFace> roof;
    if ((objs.options.roof_step || objs.options.sloped_roofs) && !occluder.empty())
      roof = roof_faces(*r, objs.file.file());
    if (objs.options.sloped_roofs && !roof.empty())
      for (RoofPrism& p : roof_prisms(occluder, r->zmin, roof, r->top))
        o.roof_prisms.push_back(std::move(p));
    if (!roof.empty() && objs.options.roof_step) {
      for (OccluderPrism& p : stepped_occluders(occluder, r->zmin, roof, *objs.options.roof_step))
        o.occluders.push_back(std::move(p));
    } else if (r->top > r->zmin) {
      for (const Polygon& p : occluder) o.occluders.push_back({p, r->zmin, r->top});
    }
    for (Polygon& p : footprint) ground_parts.push_back(std::move(p));
  }
  o.footprint = ground_parts.size() > 1 ? union_polygons(ground_parts) : std::move(ground_parts);
  if (lost && o.occluders.empty()) {
    o.occludes = false;
    why_not = "no footprint of positive area left after repair";
  } else if (off_walls && o.occluders.empty()) {
    o.occludes = false;
    why_not = "no walls stand round its GroundSurface";
  }
  if (height_unknown) {
    // As tall as a building may be (ReadOptions::max_height); it occludes nothing.
    o.bbox.zmax = std::max(o.bbox.zmax, o.ground_z + objs.options.max_height);
    o.occludes = false;
    why_not = "only a LoD0 footprint: height unknown, tested up to --max-height";
  }
  return o;
}

// The box of every vertex a building, its parts and installations use, for a building whose
// geometry gives no occluder: it is still an object, tested over this box, and standing on the
// convex hull of those vertices.
CityObject read_building_box(const Objects& objs, const std::string& id, const Json& obj) {
  std::vector<std::pair<std::string, const Json*>> members;
  objs.collect_parts(id, obj, members, 0);
  CityObject o;
  o.source_id = id;
  std::vector<Vec2> points;
  const auto add = [&](const Vertex& v) {
    o.bbox.extend(Vec2{v[0], v[1]}, v[2]);
    points.push_back({v[0], v[1]});
  };
  for (const auto& [pid, pobj] : members) {
    const Json* g = chosen_geometry(*pobj);
    if (!g) continue;
    for (const Surface& sf : surfaces_of(*g, objs.file.file(), pid))
      for (const Json& ring : *sf.rings)
        for (const Vertex& v : ring_vertices(objs.file, ring, pid)) add(v);
  }
  objs.for_each_installation_surface(members, [&](const Surface3& sf) {
    for (const auto& r : sf.rings)
      for (const Vertex& v : r) add(v);
  });
  o.ground_z = o.bbox.zmin;
  // What it takes out of free space: the hull, not the box, which covers twice the area of a
  // building turned 45 degrees.
  if (Ring hull = convex_hull(points); !hull.empty()) o.footprint = {Polygon{std::move(hull), {}}};
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
  scan.kind =
      is_geographic_crs(scan.crs) ? LocalFrame::Kind::Geographic : LocalFrame::Kind::Projected;
  return scan;
}

void load_cityjson(const Json& doc, const std::string& file, const LocalFrameMapping& mapping,
                   const ReadOptions& options, City& city) {
  CityJsonFile f(doc, file, &mapping);
  const Json& all = f.objects();
  Objects objs{f, {}, options, city.report, {}};
  for (auto it = all.begin(); it != all.end(); ++it) objs.by_id.emplace(it.key(), &it.value());
  // BuildingInstallations and any other child of a Building or BuildingPart (by its "parents")
  // are read with that building, not as objects or ignored types of their own.
  std::unordered_map<std::string, bool> installation;
  for (auto it = all.begin(); it != all.end(); ++it) {
    const std::string type = string_member(it.value(), "type");
    if (type == "Building" || type == "BuildingPart" || type == "TINRelief") continue;
    if (std::string parent = objs.building_parent(it.value()); !parent.empty()) {
      objs.installations[parent].push_back(it.key());
      installation[it.key()] = true;
      ++city.report.installations;
    }
  }

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
    if (installation.count(id)) continue;  // read with its building
    const bool building = type == "Building" || type == "BuildingPart";
    if (!building) {
      ++city.report.ignored_types[type.empty() ? "(no type)" : type];
      continue;
    }
    if (objs.read_with_parent(id, obj)) continue;
    if (type == "BuildingPart")
      city.report.warnings.push_back(file + ": " + id +
                                     ": BuildingPart that no Building lists among its "
                                     "children, read as a building of its own");
    CityObject o;
    std::string why_not;
    // The building's own attribute (not its parts'): the object a PVS lists is the building.
    const std::string payload =
        obj.contains("attributes") ? payload_of(obj["attributes"], options.payload_key) : "";
    try {
      o = read_building(objs, id, obj, why_not);
      o.payload = payload;
    } catch (const InputError& e) {
      if (options.strict || e.problem() != InputProblem::InvalidGeometry) throw;
      o = read_building_box(objs, id, obj);
      o.payload = payload;
      if (o.bbox.xy.empty()) {  // not one position left to place it by
        city.report.warnings.push_back(std::string(e.what()) + " (no coordinates: skipped)");
        continue;
      }
      city.objects.push_back(non_occluding(std::move(o), e.what(), city.report));
      continue;
    }
    if (o.bbox.xy.empty()) {
      city.report.warnings.push_back(file + ": " + id +
                                     ": building without usable geometry "
                                     "(no LoD1/LoD2 solid or surface) skipped");
      continue;
    }
    check_plausible(o, options, file);
    if (!o.occludes) {
      // A part may be missing from its footprint: it stands on the hull of all it has.
      if (Ring hull = object_hull(o); !hull.empty()) o.footprint = {Polygon{std::move(hull), {}}};
      city.objects.push_back(
          non_occluding(std::move(o), file + ": " + id + ": " + why_not, city.report));
      continue;
    }
    city.objects.push_back(std::move(o));
  }
}

}  // namespace urbanpvs::geometry::detail
