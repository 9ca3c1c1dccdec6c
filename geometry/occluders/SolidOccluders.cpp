// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/occluders/SolidOccluders.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "FaceTriangulation.hpp"
#include "LatticeMask.hpp"

#if URBANPVS_HAVE_TETGEN
#define TETLIBRARY
#include <tetgen.h>
#endif

namespace urbanpvs::geometry {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Raster squares of ε/2: the column test widens ε by half a square (a quarter of ε), and a
// 30 m building takes 60 × 60 columns at the default ε.
constexpr double kSquarePerEpsilon = 0.5;
// A building's plan takes at most this many columns (8 MB of tops): 1 km square at ε = 1 m.
constexpr double kMaxColumns = 4.0e6;
// Vertices closer than this are one vertex of the solid (the input's own precision is a
// millimetre at best).
constexpr double kWeld = 1e-4;  // [Units: m]
// An open loop of edges this close to the ground is the solid's missing bottom.
constexpr double kCapRise = 0.25;  // [Units: m]
// Where faces close no volume as given: another face's edge whose ends lie this close to a
// face's plane, inside the face, cuts it (cut_faces_along_edges_in_them), and a vertex this close
// to an edge splits it. Real faces are planar to their coordinates' rounding (Zürich's to about
// 1 mm: of the wall corners inside its roofs, 1,096 lie within 1 mm of the roof's plane, 22 more
// within 1 cm; its gables' apexes end up to a millimetre beside the ridge).
constexpr double kInPlane = 0.005;  // [Units: m]
// A face whose normal points this far down (the cosine of its angle to the vertical) is an
// underside: steeper ones are walls.
constexpr double kFacesDown = 0.5;
// A column must stand in the solid from this far above the ground: an outside that only
// touches the ground plane (the air under a floor slab at ground level) holds nothing down.
constexpr double kAboveGround = 0.01;  // [Units: m]
// The column's box is narrowed by this: the outside's tetrahedra share the solid's faces, and
// one that only touches the box where a face bounds it takes nothing from the column.
constexpr double kTouch = 1e-7;  // [Units: m]

/// The z range of a tetrahedron within a vertical column over `box` (empty: lo > hi).
struct ZRange {
  double lo = kInfinity, hi = -kInfinity;
  void add(double z) {
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
};

bool in_box(const Box2& b, double x, double y) {
  return x >= b.min.x && x <= b.max.x && y >= b.min.y && y <= b.max.y;
}

/// The lowest and highest points of t ∩ (box × ℝ). Both are vertices of that polytope, and
/// each such vertex is a corner of t in the column, a crossing of an edge of t with a side of
/// the column, or a crossing of a vertical edge of the column with a face of t.
ZRange column_range(const std::array<Vec3, 4>& t, const Box2& box) {
  ZRange r;
  for (const Vec3& v : t)
    if (in_box(box, v.x, v.y)) r.add(v.z);
  static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (const auto& e : kEdges) {
    const Vec3& p = t[static_cast<std::size_t>(e[0])];
    const Vec3& q = t[static_cast<std::size_t>(e[1])];
    for (const double x : {box.min.x, box.max.x}) {
      if (p.x == q.x || (p.x - x) * (q.x - x) > 0) continue;
      const double s = (x - p.x) / (q.x - p.x);
      const double y = p.y + s * (q.y - p.y);
      if (y >= box.min.y && y <= box.max.y) r.add(p.z + s * (q.z - p.z));
    }
    for (const double y : {box.min.y, box.max.y}) {
      if (p.y == q.y || (p.y - y) * (q.y - y) > 0) continue;
      const double s = (y - p.y) / (q.y - p.y);
      const double x = p.x + s * (q.x - p.x);
      if (x >= box.min.x && x <= box.max.x) r.add(p.z + s * (q.z - p.z));
    }
  }
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (const auto& f : kFaces) {
    const Vec3& a = t[static_cast<std::size_t>(f[0])];
    const Vec3& b = t[static_cast<std::size_t>(f[1])];
    const Vec3& c = t[static_cast<std::size_t>(f[2])];
    const double d = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (std::abs(d) < 1e-12) continue;  // a vertical face: its corners in the column are above
    for (const double x : {box.min.x, box.max.x})
      for (const double y : {box.min.y, box.max.y}) {
        const double lb = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / d;
        const double lc = ((a.x - x) * (b.y - y) - (b.x - x) * (a.y - y)) / d;
        const double la = 1 - lb - lc;
        if (la >= -1e-12 && lb >= -1e-12 && lc >= -1e-12) r.add(la * a.z + lb * b.z + lc * c.z);
      }
  }
  return r;
}

/// The solid's faces as a TetGen PLC: welded vertices (around `centre`, for the predicates'
/// sake) and polygons of three or more distinct vertices, each face once.
struct Plc {
  std::vector<Vec3> points;
  /// Each face's rings, outer first; after triangulation, one ring of three per face.
  std::vector<std::vector<std::vector<int>>> faces;
  std::string problem;  ///< why the surfaces cannot be meshed as given
};

/// Why a solid gives nothing when its faces, even cut, leave the outside a way in.
constexpr const char* kCloseNoVolume = "its faces close no volume";

using Edge = std::pair<int, int>;  ///< its two vertices, the smaller first

/// Calls f with every edge of every ring of `face`.
template <class F>
void for_each_edge(const std::vector<std::vector<int>>& face, F f) {
  for (const std::vector<int>& r : face)
    for (std::size_t k = 0; k < r.size(); ++k) {
      const int a = r[k], b = r[(k + 1) % r.size()];
      f(a < b ? Edge{a, b} : Edge{b, a}, a, b);
    }
}

/// How many faces have each edge.
std::map<Edge, int> edge_uses(const Plc& plc) {
  std::map<Edge, int> uses;
  for (const auto& face : plc.faces) for_each_edge(face, [&](Edge e, int, int) { ++uses[e]; });
  return uses;
}

/// Removes, until none is left, every face with an edge that no other face has. Such a face
/// bounds no volume: a LoD0 footprint that a reader keeps beside the solid, or a wall of a shell
/// with a gap. Left in, it would cut through the solid, which is no PLC; taken out, a closed
/// solid loses nothing and an open one stays open.
void drop_open_faces(Plc& plc) {
  for (bool dropped = true; dropped;) {
    dropped = false;
    std::map<Edge, int> uses = edge_uses(plc);
    std::vector<std::vector<std::vector<int>>> kept;
    for (auto& face : plc.faces) {
      bool open = false;
      for_each_edge(face, [&](Edge e, int, int) { open = open || uses[e] < 2; });
      if (open)
        dropped = true;
      else
        kept.push_back(std::move(face));
    }
    plc.faces = std::move(kept);
  }
}

/// Inserts into every face edge the vertices that lie on it, within `tolerance`. Faces of real
/// solids often meet in T-junctions (a wall's top edge runs past the corner of the part on it),
/// and a PLC whose vertex lies inside another face's edge is invalid: TetGen crashes on it.
void split_at_t_junctions(Plc& plc, double tolerance) {
  std::vector<int> split;
  std::vector<std::pair<double, int>> on_edge;
  for (auto& face : plc.faces)
    for (std::vector<int>& ring : face) {
      split.clear();
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const int a = ring[k], b = ring[(k + 1) % ring.size()];
        split.push_back(a);
        const Vec3 p = plc.points[static_cast<std::size_t>(a)];
        const Vec3 d = plc.points[static_cast<std::size_t>(b)] - p;
        const double length2 = glm::dot(d, d);
        if (length2 == 0) continue;
        on_edge.clear();
        for (std::size_t v = 0; v < plc.points.size(); ++v) {
          if (static_cast<int>(v) == a || static_cast<int>(v) == b) continue;
          const Vec3 w = plc.points[v] - p;
          const double t = glm::dot(w, d) / length2;
          if (t <= 0 || t >= 1) continue;
          const Vec3 off = w - t * d;
          if (glm::dot(off, off) <= tolerance * tolerance)
            on_edge.emplace_back(t, static_cast<int>(v));
        }
        std::sort(on_edge.begin(), on_edge.end());
        for (const auto& [t, v] : on_edge) split.push_back(v);
      }
      ring = split;
    }
}

/// The face's rings in the plane across axis `drop` (planar()), outer first.
Polygon planar_face(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& rings,
                    int drop) {
  Polygon plan;
  for (std::size_t r = 0; r < rings.size(); ++r) {
    Ring& ring = r == 0 ? plan.outer : plan.holes.emplace_back();
    for (const int v : rings[r]) ring.push_back(planar(points[static_cast<std::size_t>(v)], drop));
  }
  return plan;
}

/// Cuts each face along the edges of other faces that lie in it. A roof that overhangs its
/// walls reaches past their tops, and the walls end inside it (Zürich's LoD2 models): each wall's
/// top edge is then an edge of the wall only, and the solid does not close. Cut along the wall
/// tops, the roof becomes triangles over the walls and triangles of the eaves; the eaves' outer
/// edges are open, so drop_open_faces takes them away triangle by triangle, and what remains
/// closes under the roof. An edge lies in the face when both its ends are within kInPlane of the
/// face's plane and its middle inside the face; a face whose cuts cross each other or its rings
/// stays as it was.
void cut_faces_along_edges_in_them(Plc& plc) {
  std::set<Edge> edges;
  for (const auto& face : plc.faces)
    for_each_edge(face, [&](Edge e, int, int) { edges.insert(e); });
  std::vector<std::vector<std::vector<int>>> faces;
  std::vector<std::pair<int, int>> cuts;
  std::vector<std::array<int, 3>> triangles;
  for (auto& face : plc.faces) {
    const std::vector<int>& outer = face.front();
    const Vec3 n = newell_normal(outer.size(), [&](std::size_t k) {
      return plc.points[static_cast<std::size_t>(outer[k])];
    });
    const double length = glm::length(n);
    if (!(length > 0)) {
      faces.push_back(std::move(face));
      continue;
    }
    const Vec3 unit = n / length;
    double offset = 0;
    Box3 box;
    for (const int v : outer) {
      const Vec3& p = plc.points[static_cast<std::size_t>(v)];
      offset += glm::dot(unit, p);
      box.extend(Vec2{p.x, p.y}, p.z);
    }
    offset /= static_cast<double>(outer.size());
    const int drop = dominant_axis(n);
    const Polygon plan = planar_face(plc.points, face, drop);
    std::set<Edge> own;
    for_each_edge(face, [&](Edge e, int, int) { own.insert(e); });
    auto in_plane = [&](int v) {
      const Vec3& p = plc.points[static_cast<std::size_t>(v)];
      return std::abs(glm::dot(unit, p) - offset) <= kInPlane &&
             box.xy.grown(kInPlane).overlaps({{p.x, p.y}, {p.x, p.y}}) &&
             p.z >= box.zmin - kInPlane && p.z <= box.zmax + kInPlane;
    };
    cuts.clear();
    for (const Edge& e : edges) {
      if (own.contains(e) || !in_plane(e.first) || !in_plane(e.second)) continue;
      const Vec3 middle = 0.5 * (plc.points[static_cast<std::size_t>(e.first)] +
                                 plc.points[static_cast<std::size_t>(e.second)]);
      if (inside(plan, planar(middle, drop))) cuts.push_back(e);
    }
    triangles.clear();
    if (cuts.empty() || !triangulate_face(plc.points, face, cuts, triangles)) {
      faces.push_back(std::move(face));
      continue;
    }
    // The triangles run counter-clockwise in the plane of `drop`: the face's own way round
    // when its normal points along that axis, else reversed.
    const bool reverse = n[drop] < 0;
    for (const std::array<int, 3>& t : triangles)
      faces.push_back(
          {reverse ? std::vector<int>{t[0], t[2], t[1]} : std::vector<int>{t[0], t[1], t[2]}});
  }
  plc.faces = std::move(faces);
}

/// Closes the solid's open bottom: each loop of edges that one face only has, lying within
/// kCapRise of the ground, becomes a face. LoD2 models often leave out the ground surface
/// (the Delft sample derives its footprints from the roofs), and the occluders stand on the
/// ground anyway (thesis 4.2.1), so closing the solid there assumes nothing they do not.
void cap_ground_loops(Plc& plc, double ground) {
  std::map<Edge, int> uses = edge_uses(plc);
  // A face that shares no edge with any other stands alone (a LoD0 footprint kept beside the
  // solid): its outline is no opening of the shell, and it goes before any loop is capped.
  std::erase_if(plc.faces, [&](const std::vector<std::vector<int>>& face) {
    bool shared = false;
    for_each_edge(face, [&](Edge e, int, int) { shared = shared || uses[e] > 1; });
    if (!shared) for_each_edge(face, [&](Edge e, int, int) { --uses[e]; });
    return !shared;
  });
  std::map<int, int> next;  // the open edges, as their faces run
  bool branching = false;
  for (const auto& face : plc.faces)
    for_each_edge(face, [&](Edge e, int a, int b) {
      if (uses[e] == 1 && !next.emplace(a, b).second) branching = true;
    });
  if (branching) return;  // two open edges leave one vertex: no loop to trust
  while (!next.empty()) {
    std::vector<int> loop;
    int at = next.begin()->first;
    while (true) {
      const auto it = next.find(at);
      if (it == next.end()) break;
      loop.push_back(at);
      at = it->second;
      next.erase(it);
    }
    const bool closed = !loop.empty() && at == loop.front();
    const bool low = std::all_of(loop.begin(), loop.end(), [&](int v) {
      return plc.points[static_cast<std::size_t>(v)].z <= ground + kCapRise;
    });
    if (closed && low && loop.size() >= 3)
      plc.faces.push_back({std::vector<int>(loop.rbegin(), loop.rend())});
  }
}

/// The PLC of the solid's faces. `cut`: the faces are also cut along the edges of others that
/// lie in them (cut_faces_along_edges_in_them), and a vertex within kInPlane of an edge is put
/// on it (the gable's apex of an overhanging roof, which ends within a few millimetres of the
/// ridge).
Plc plc_of(const std::vector<Surface3>& surfaces, const Vec3& centre, double ground, bool cut) {
  Plc plc;
  std::map<std::array<long long, 3>, int> index;
  std::set<std::vector<int>> seen;
  for (const Surface3& s : surfaces) {
    if (!s.blocks) {
      plc.problem = "a surface bounds where the building may be, not where it is";
      return plc;
    }
    std::vector<std::vector<int>> face;
    for (const std::vector<Vec3>& input : s.rings) {
      std::vector<int> ring;
      for (const Vec3& v : input) {
        const Vec3 p = v - centre;
        const std::array<long long, 3> key = {std::llround(p.x / kWeld), std::llround(p.y / kWeld),
                                              std::llround(p.z / kWeld)};
        auto [it, added] = index.emplace(key, static_cast<int>(plc.points.size()));
        if (added) plc.points.push_back(p);
        if (ring.empty() || ring.back() != it->second) ring.push_back(it->second);
      }
      while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
      if (ring.size() >= 3)
        face.push_back(std::move(ring));
      else if (face.empty())
        break;  // an outer ring of no area: the face has none
    }
    if (face.empty()) continue;
    std::vector<int> key;
    for (const std::vector<int>& r : face) key.insert(key.end(), r.begin(), r.end());
    std::sort(key.begin(), key.end());
    if (std::unique(key.begin(), key.end()) - key.begin() < 3) continue;  // no area
    if (!seen.insert(key).second) continue;  // the face two parts share
    plc.faces.push_back(std::move(face));
  }
  split_at_t_junctions(plc, cut ? kInPlane : kWeld);
  if (cut) cut_faces_along_edges_in_them(plc);
  cap_ground_loops(plc, ground);
  drop_open_faces(plc);
  if (plc.faces.size() < 4) {
    plc.problem = kCloseNoVolume;
    return plc;
  }
  // TetGen meshes each facet in its plane: a face of real data is planar only to its
  // coordinates' rounding, and meshed in a plane of its own it crosses its neighbours. Its
  // triangles are planar whatever the rounding.
  std::vector<std::array<int, 3>> triangles;
  for (const auto& face : plc.faces)
    if (!triangulate_face(plc.points, face, triangles)) {
      plc.problem = "a face whose rings cross";
      return plc;
    }
  plc.faces.clear();
  for (const std::array<int, 3>& t : triangles) plc.faces.push_back({{t[0], t[1], t[2]}});
  return plc;
}

/// The exterior tetrahedra of the solid within `outer` (a box around it, relative to the
/// PLC's centre), or a reason in `problem`.
std::vector<std::array<Vec3, 4>> exterior_tetrahedra(const Plc& plc, const Vec3& lo, const Vec3& hi,
                                                     std::string& problem) {
#if !URBANPVS_HAVE_TETGEN
  (void)plc, (void)lo, (void)hi;
  problem = "built without TetGen (URBANPVS_TETGEN=OFF)";
  return {};
#else
  tetgenio in, out;
  in.firstnumber = 0;
  const std::size_t n = plc.points.size();
  in.numberofpoints = static_cast<int>(n + 8);
  in.pointlist = new REAL[3 * (n + 8)];
  for (std::size_t k = 0; k < n; ++k) {
    in.pointlist[3 * k] = plc.points[k].x;
    in.pointlist[3 * k + 1] = plc.points[k].y;
    in.pointlist[3 * k + 2] = plc.points[k].z;
  }
  for (std::size_t c = 0; c < 8; ++c) {  // the box's corners: bit 0 x, bit 1 y, bit 2 z
    in.pointlist[3 * (n + c)] = (c & 1) ? hi.x : lo.x;
    in.pointlist[3 * (n + c) + 1] = (c & 2) ? hi.y : lo.y;
    in.pointlist[3 * (n + c) + 2] = (c & 4) ? hi.z : lo.z;
  }
  static constexpr int kBoxFaces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                          {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  const std::size_t faces = plc.faces.size() + 6;
  in.numberoffacets = static_cast<int>(faces);
  in.facetlist = new tetgenio::facet[faces];
  for (std::size_t f = 0; f < faces; ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    facet.numberofholes = 0;
    facet.holelist = nullptr;
    tetgenio::polygon& polygon = facet.polygonlist[0];
    if (f < plc.faces.size()) {
      const std::vector<int>& face = plc.faces[f].front();
      polygon.numberofvertices = static_cast<int>(face.size());
      polygon.vertexlist = new int[face.size()];
      std::copy(face.begin(), face.end(), polygon.vertexlist);
    } else {
      polygon.numberofvertices = 4;
      polygon.vertexlist = new int[4];
      for (int k = 0; k < 4; ++k)
        polygon.vertexlist[k] = static_cast<int>(n) + kBoxFaces[f - plc.faces.size()][k];
    }
  }
  // One seed in the box's corner, outside the solid: with -A, the tetrahedra it reaches
  // without crossing a face get its attribute, every enclosed region another. (Mistaking the
  // inside for the outside would only take columns away.)
  constexpr REAL kOutside = -1;  // TetGen numbers the regions without a seed from 1 up
  in.numberofregions = 1;
  in.regionlist = new REAL[5]{lo.x + 0.25, lo.y + 0.25, lo.z + 0.25, kOutside, -1};
  try {
    // Faces that cross each other are not a PLC, and TetGen 1.5 may crash on them instead of
    // refusing them: its -d pass lists such faces without meshing, so it goes first.
    {
      tetgenio check;
      char detect[] = "pdQ";
      tetrahedralize(detect, &in, &check);
      if (check.numberoftrifaces > 0) {
        problem = "its faces intersect each other (TetGen -d)";
        return {};
      }
    }
    char switches[] = "pQA";
    tetrahedralize(switches, &in, &out);
  } catch (int code) {
    problem = "TetGen refused the surfaces (error " + std::to_string(code) +
              (code == 3 ? ": they intersect each other)" : ")");
    return {};
  } catch (...) {
    problem = "TetGen failed on the surfaces";
    return {};
  }
  std::vector<std::array<Vec3, 4>> exterior;
  if (out.numberoftetrahedronattributes < 1) {
    problem = "TetGen gave no regions";
    return exterior;
  }
  const int corners = out.numberofcorners;
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    if (out.tetrahedronattributelist[static_cast<std::size_t>(t) *
                                     static_cast<std::size_t>(out.numberoftetrahedronattributes)] !=
        kOutside)
      continue;
    std::array<Vec3, 4> tet;
    for (std::size_t k = 0; k < 4; ++k) {
      const auto p = static_cast<std::size_t>(
          out.tetrahedronlist[static_cast<std::size_t>(t) * static_cast<std::size_t>(corners) + k]);
      tet[k] = {out.pointlist[3 * p], out.pointlist[3 * p + 1], out.pointlist[3 * p + 2]};
    }
    exterior.push_back(tet);
  }
  return exterior;
#endif
}

}  // namespace

bool overhangs(const std::vector<Surface3>& surfaces, double ground_z) {
  for (const Surface3& s : surfaces) {
    if (s.rings.empty() || s.rings.front().size() < 3) continue;
    const std::vector<Vec3>& r = s.rings.front();
    const Vec3 n = newell_normal(r.size(), [&](std::size_t k) { return r[k]; });
    const double low = std::min_element(r.begin(), r.end(), [](const Vec3& a, const Vec3& b) {
                         return a.z < b.z;
                       })->z;
    if (n.z < -kFacesDown * glm::length(n) && low > ground_z + kCapRise) return true;
  }
  return false;
}

bool solid_shrinking_available() {
  return URBANPVS_HAVE_TETGEN != 0;
}

namespace {

// shrink_solid for one closed solid (ε and step checked).
ShrunkSolid shrink_closed(const std::vector<Surface3>& surfaces, double ground_z, double epsilon,
                          double step) {
  ShrunkSolid result;
  Box3 extent;
  for (const Surface3& s : surfaces)
    for (const auto& ring : s.rings)
      for (const Vec3& v : ring) extent.extend(Vec2{v.x, v.y}, v.z);
  if (extent.xy.empty()) {
    result.declined = "no surfaces";
    return result;
  }
  const Vec3 centre = {(extent.xy.min.x + extent.xy.max.x) / 2,
                       (extent.xy.min.y + extent.xy.max.y) / 2, (extent.zmin + extent.zmax) / 2};
  // Faces as they are first; cut only where they close no volume so (a roof that overhangs
  // its walls): the cuts' larger tolerance would bend faces of solids that close without it.
  Plc plc = plc_of(surfaces, centre, ground_z - centre.z, false);
  if (plc.problem == kCloseNoVolume) {
    Plc cut = plc_of(surfaces, centre, ground_z - centre.z, true);
    if (cut.problem.empty()) plc = std::move(cut);
  }
  if (!plc.problem.empty()) {
    result.declined = plc.problem;
    return result;
  }
  // The columns: squares over the solid's plan, each tested with a box of half-side
  // ε + square / 2 around its centre (a point's disk of radius ε lies in it).
  // At most kMaxColumns columns: a larger plan takes larger squares (each loses half of its
  // side more, which only ever takes columns away).
  double square = kSquarePerEpsilon * epsilon;
  const double width = extent.xy.max.x - extent.xy.min.x, depth = extent.xy.max.y - extent.xy.min.y;
  while ((std::ceil(width / square) + 1) * (std::ceil(depth / square) + 1) > kMaxColumns)
    square *= 1.25;
  const double reach = epsilon + square / 2 - kTouch;
  const Box2 plan = {{extent.xy.min.x - centre.x, extent.xy.min.y - centre.y},
                     {extent.xy.max.x - centre.x, extent.xy.max.y - centre.y}};
  const int columns = std::max(1, static_cast<int>(std::ceil((plan.max.x - plan.min.x) / square)));
  const int rows = std::max(1, static_cast<int>(std::ceil((plan.max.y - plan.min.y) / square)));
  // The meshed box reaches past every column's test box, and a metre below and above.
  const double margin = reach + 1;
  // Down to the ground, wherever that is: air between the ground and a raised solid must be
  // meshed to be found.
  const Vec3 lo = {plan.min.x - margin, plan.min.y - margin,
                   std::min(extent.zmin, ground_z) - centre.z - 1};
  const Vec3 hi = {plan.min.x + columns * square + margin, plan.min.y + rows * square + margin,
                   extent.zmax - centre.z + 1};
  const std::vector<std::array<Vec3, 4>> exterior =
      exterior_tetrahedra(plc, lo, hi, result.declined);
  if (!result.declined.empty()) return result;
  result.exterior_tetrahedra = exterior.size();

  // Each column's top: the lowest point, above the ground, of the outside within its box.
  const double floor_z = ground_z - centre.z + kAboveGround;
  std::vector<double> top(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows),
                          kInfinity);
  for (const std::array<Vec3, 4>& t : exterior) {
    Box2 b;
    for (const Vec3& v : t) b.extend(Vec2{v.x, v.y});
    auto first = [&](double from, double origin) {
      return static_cast<int>(std::floor((from - reach - origin) / square - 0.5));
    };
    auto last = [&](double to, double origin) {
      return static_cast<int>(std::ceil((to + reach - origin) / square - 0.5));
    };
    const int i0 = std::max(0, first(b.min.x, plan.min.x));
    const int i1 = std::min(columns - 1, last(b.max.x, plan.min.x));
    const int j0 = std::max(0, first(b.min.y, plan.min.y));
    const int j1 = std::min(rows - 1, last(b.max.y, plan.min.y));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec2 c = {plan.min.x + (i + 0.5) * square, plan.min.y + (j + 0.5) * square};
        const ZRange r = column_range(t, {{c.x - reach, c.y - reach}, {c.x + reach, c.y + reach}});
        if (r.lo > r.hi || r.hi < floor_z) continue;  // misses the column, or under the ground
        double& z = top[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) +
                        static_cast<std::size_t>(i)];
        z = std::min(z, std::max(r.lo, floor_z));
      }
  }

  // Levels every `step` above the ground, each top rounded down onto one.
  std::vector<double> level(top.size(), -kInfinity);
  std::set<double, std::greater<>> tops;
  for (std::size_t k = 0; k < top.size(); ++k) {
    const double base = ground_z - centre.z;
    // Rounding in the tops' interpolation is forgiven up to kTouch: a roof at 10 m stays a
    // level at 10 m when its column's top comes out as 10 - 1e-15.
    double h = base + std::floor((top[k] + kTouch - base) / step) * step;
    if (h > top[k] + kTouch) h -= step;
    if (!(h > floor_z) || !std::isfinite(h)) continue;
    level[k] = h;
    tops.insert(h);
  }
  std::vector<double> xs(static_cast<std::size_t>(columns) + 1),
      ys(static_cast<std::size_t>(rows) + 1);
  for (std::size_t i = 0; i < xs.size(); ++i)
    xs[i] = plan.min.x + static_cast<double>(i) * square + centre.x;
  for (std::size_t j = 0; j < ys.size(); ++j)
    ys[j] = plan.min.y + static_cast<double>(j) * square + centre.y;
  for (const double h : tops) {
    LatticeMask mask(xs, ys);
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < columns; ++i)
        mask.set(i, j,
                 level[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) +
                       static_cast<std::size_t>(i)] >= h);
    mask.separate_diagonals();
    std::vector<Polygon> shapes;
    // Rings that do not assemble are left out: an occluder may always be smaller.
    if (!mask.polygons(shapes)) continue;
    for (Polygon& p : shapes) {
      const Box2 box = bounds(p);
      result.occluders.push_back({kSolidBlock, h + centre.z, std::move(p), box});
    }
  }
  if (tops.empty()) result.declined = "no column stands in the solid at least ε from its outside";
  return result;
}

}  // namespace

ShrunkSolid shrink_solid(const std::vector<Surface3>& surfaces, double ground_z, double epsilon,
                         double step) {
  if (!(epsilon > 0) || !(step > 0)) return {{}, 0, "ε and the level step must be positive"};
  ShrunkSolid whole = shrink_closed(surfaces, ground_z, epsilon, step);
  if (!whole.occluders.empty()) return whole;
  // Parts that meet inside each other's faces (a dormer's closed box standing on a roof face
  // that is not cut around it) do not make one solid: their coplanar faces overlap, or a
  // part's edge ends inside a face, and the whole gives nothing. Each part alone may close. A
  // part lies in the building, so what its shrinking keeps is inside the building at least ε
  // from the part's outside, and so from the building's: the union of the parts' occluders is
  // conservative, only smaller than the whole's would be by the ε each part loses at the faces
  // it shares. Installations give no occluder (no volume a prism from the ground may fill).
  std::vector<std::uint32_t> parts;
  for (const Surface3& s : surfaces)
    if (s.part != Surface3::kInstallation) parts.push_back(s.part);
  std::sort(parts.begin(), parts.end());
  parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
  if (parts.size() < 2) return whole;
  ShrunkSolid joined;
  std::vector<Surface3> alone;
  for (const std::uint32_t part : parts) {
    alone.clear();
    for (const Surface3& s : surfaces)
      if (s.part == part) alone.push_back(s);
    ShrunkSolid r = shrink_closed(alone, ground_z, epsilon, step);
    joined.exterior_tetrahedra += r.exterior_tetrahedra;
    for (Occluder& o : r.occluders) joined.occluders.push_back(std::move(o));
  }
  if (joined.occluders.empty()) return whole;
  return joined;
}

}  // namespace urbanpvs::geometry
