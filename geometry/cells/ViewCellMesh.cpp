// SPDX-License-Identifier: GPL-3.0-or-later
// View cells as a refined constrained Delaunay triangulation of free space (thesis 5.3). Kept in
// its own translation unit: CGAL's CDT and mesher take ~12 s and 850 MB to compile at -O2
// (measured).
//
// Pass 1 inserts every footprint ring and every region ring as a polyline constraint, unchanged:
// the triangulation splits them where they cross or touch, and free space is classified by
// winding numbers, so buildings that share walls, touch at corners, overlap or nest (a tower on
// its podium) need no Boolean union first and leave no sliver between them (thesis 5.4). Pass 2
// triangulates the boundary of free space alone and refines it with CGAL's Delaunay mesher.
//
// Cells must never enter a building (thesis 5.3: "occluders cannot intersect view cells"), and
// that is kept exact: the only inexact points, the mesher's midpoints of slanted walls and the
// crossings of footprints, are moved by a few units in the last place onto the free side when
// rounding put them inside a building.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>

#include "BoxGrid.hpp"
#include "FreeSpaceTriangulation.hpp"
#include "RingLocator.hpp"
#include "WindingNumbers.hpp"

namespace urbanpvs::geometry::detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_2;

// Winding numbers of a face: how many obstacles (kind 0) and how many region polygons (kind 1)
// contain it.
struct FaceInfo {
  std::array<int, 2> winding{};
  bool seen = false;
  std::int32_t index = -1;  // output triangle, -1 for faces outside free space
};

using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<
    K, CGAL::Constrained_Delaunay_triangulation_face_base_2<
           K, CGAL::Constrained_triangulation_face_base_2<
                  K, CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>>>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact_predicates_tag: footprints of real cities cross each other; the crossings are computed
// (rounded) and inserted as vertices.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
// The "plus" hierarchy remembers which input ring every constrained edge came from, also after
// the mesher split it: that is what the winding numbers are computed from.
using Cdtp = CGAL::Constrained_triangulation_plus_2<Cdt>;
using SizeCriteria = CGAL::Delaunay_mesh_size_criteria_2<Cdtp>;

// Shewchuk's shape bound with a floor: Delaunay refinement does not terminate well near small
// input angles (it chases them into ever smaller triangles), so a triangle whose shortest edge
// is already below `min_edge` is left as it is. A badly shaped cell is still a valid cell for
// point location and sampling; the size bound still holds everywhere.
class CellCriteria : public SizeCriteria {
 public:
  CellCriteria(double shape_bound, double max_edge, double min_edge)
      : SizeCriteria(shape_bound, max_edge), min_edge_(min_edge) {}

  class Is_bad : public SizeCriteria::Is_bad {
   public:
    Is_bad(const SizeCriteria::Is_bad& base, double min_edge)
        : SizeCriteria::Is_bad(base), squared_min_edge_(min_edge * min_edge) {}
    using SizeCriteria::Is_bad::operator();
    CGAL::Mesh_2::Face_badness operator()(const Face_handle& f, Quality& q) const {
      const CGAL::Mesh_2::Face_badness b = SizeCriteria::Is_bad::operator()(f, q);
      if (b != CGAL::Mesh_2::BAD) return b;
      double shortest = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k)
        shortest = std::min(shortest, CGAL::squared_distance(f->vertex(k)->point(),
                                                             f->vertex(Cdtp::ccw(k))->point()));
      if (shortest >= squared_min_edge_) return b;
      q.first = 1;  // a quality that reads as well shaped when the mesher looks at it again
      return CGAL::Mesh_2::NOT_BAD;
    }

   private:
    double squared_min_edge_;
  };

  Is_bad is_bad_object() const { return Is_bad(SizeCriteria::is_bad_object(), min_edge_); }

 private:
  double min_edge_;
};

// Gabriel conformity with a floor, the edge-level twin of CellCriteria. CGAL's mesher splits every
// constrained edge whose diametral circle holds a vertex. Along an alley 1 m wide between two
// staircase outlines, that splits every wall into pieces as short as the alley is wide and fans
// each of them out into slivers: Delft's 59,095 m² of free space got 1,640 cells, 1.61 times the
// density of a generated city. A wall piece already shorter than the floor (the same floor as
// CellCriteria's) is therefore taken as it is; a circumcentre that would encroach upon it, or
// that lies outside free space, is not inserted (the face stays as it is, like a face under the
// shape floor). Longer walls are split as before, so the size bound holds and the cells of open
// space are as they were (the generated 1 km² city, seed 7: 12,367 -> 12,158 cells).
//
// CGAL default-constructs this predicate inside its edge level, so the floor is handed over in
// a thread-local set around one refinement (ScopedWallFloor).
thread_local double squared_wall_floor = 0;

struct ScopedWallFloor {
  explicit ScopedWallFloor(double floor) { squared_wall_floor = floor * floor; }
  ~ScopedWallFloor() { squared_wall_floor = 0; }
  ScopedWallFloor(const ScopedWallFloor&) = delete;
  ScopedWallFloor& operator=(const ScopedWallFloor&) = delete;
};

bool below_wall_floor(const Point& a, const Point& b) {
  return CGAL::squared_distance(a, b) < squared_wall_floor;
}

// True when p lies outside the closed diametral circle of ab (CGAL's Gabriel test).
bool outside_diametral_circle(const Point& a, const Point& b, const Point& p) {
  return CGAL::angle(a, p, b) == CGAL::ACUTE;
}

struct ConformingAboveFloor {
  using Tr = Cdtp;
  bool operator()(const Tr& tr, const Tr::Face_handle& fh, int i) const {
    const Tr::Vertex_handle va = fh->vertex(Tr::cw(i));
    const Tr::Vertex_handle vb = fh->vertex(Tr::ccw(i));
    if (below_wall_floor(va->point(), vb->point())) return true;
    const Tr::Vertex_handle vi = fh->vertex(i);
    const Tr::Vertex_handle mvi = tr.tds().mirror_vertex(fh, i);
    return (tr.is_infinite(vi) ||
            outside_diametral_circle(va->point(), vb->point(), vi->point())) &&
           (tr.is_infinite(mvi) ||
            outside_diametral_circle(va->point(), vb->point(), mvi->point()));
  }
  bool operator()(const Tr& tr, const Tr::Vertex_handle& va, const Tr::Vertex_handle& vb) const {
    Tr::Face_handle fh;
    int i = 0;
    [[maybe_unused]] const bool found = tr.is_edge(va, vb, fh, i);
    CGAL_assertion(found);
    return (*this)(tr, fh, i);
  }
  bool operator()(const Tr& tr, const Tr::Face_handle& fh, int i, const Point& p) const {
    return (*this)(tr, fh->vertex(Tr::cw(i)), fh->vertex(Tr::ccw(i)), p);
  }
  bool operator()(const Tr&, const Tr::Vertex_handle& va, const Tr::Vertex_handle& vb,
                  const Point& p) const {
    return below_wall_floor(va->point(), vb->point()) ||
           outside_diametral_circle(va->point(), vb->point(), p);
  }
};

using EdgesBase = CGAL::Mesh_2::Refine_edges_base_with_clusters<Cdtp, ConformingAboveFloor>;

// Drops a circumcentre that leaves free space or encroaches upon a wall piece below the floor,
// instead of splitting that piece; everything else as in CGAL.
class EdgesAboveFloor : public EdgesBase {
 public:
  using EdgesBase::EdgesBase;
  using Zone = CGAL::Triangulation_mesher_level_traits_2<Cdtp>::Zone;
  CGAL::Mesher_level_conflict_status test_point_conflict_from_superior_impl(const K::Point_2& p,
                                                                            Zone& z) {
    if (!z.fh->is_in_domain()) return CGAL::CONFLICT_AND_ELEMENT_SHOULD_BE_DROPPED;
    for (const auto& [fh, i] : z.boundary_edges) {
      if (!fh->is_constrained(i)) continue;
      const K::Point_2& a = fh->vertex(Cdtp::cw(i))->point();
      const K::Point_2& b = fh->vertex(Cdtp::ccw(i))->point();
      if (below_wall_floor(a, b) && !outside_diametral_circle(a, b, p))
        return CGAL::CONFLICT_AND_ELEMENT_SHOULD_BE_DROPPED;
    }
    return EdgesBase::test_point_conflict_from_superior_impl(p, z);
  }
};

// Delaunay_mesher_2 with the edge level above (its constructor and init, less the seeds).
class Mesher {
 public:
  Mesher(Cdtp& cdt, const CellCriteria& criteria)
      : criteria_(criteria),
        clusters_(cdt),
        edges_(cdt, clusters_, null_level_),
        faces_(cdt, criteria_, edges_),
        visitor_(faces_, edges_, null_visitor_) {}
  void refine_mesh() {
    clusters_.create_clusters();
    edges_.scan_triangulation();
    faces_.scan_triangulation();
    faces_.refine(visitor_);
  }

 private:
  using Edges =
      CGAL::Mesh_2::Refine_edges_with_clusters<Cdtp, ConformingAboveFloor, EdgesAboveFloor>;
  using Faces = CGAL::Mesh_2::Refine_faces<Cdtp, CellCriteria, Edges>;
  CellCriteria criteria_;
  CGAL::Null_mesher_level null_level_;
  CGAL::Null_mesh_visitor null_visitor_;
  CGAL::Mesh_2::Clusters<Cdtp> clusters_;
  Edges edges_;
  Faces faces_;
  CGAL::Mesh_2::Refine_edges_visitor_from_faces<Faces> visitor_;
};
using Vertex_handle = Cdtp::Vertex_handle;
using Face_handle = Cdtp::Face_handle;

enum Kind { kObstacle = 0, kRegion = 1 };
using CdtRing = RingConstraint<Cdtp>;

// Thesis 5.3 asks for cells in free space only: inside some region ring and inside no
// footprint (WindingNumbers.hpp).
void classify(Cdtp& cdt, const std::vector<CdtRing>& rings) {
  classify_windings(cdt, rings);
}

bool is_free(const Cdtp& cdt, Face_handle f) {
  return !cdt.is_infinite(f) && f->info().winding[kObstacle] == 0 && f->info().winding[kRegion] > 0;
}

Point to_point(Vec2 v) {
  return {v.x, v.y};
}

// Moves rounded vertices of the output onto the closed free space (see the file comment). The
// candidates are the points a few ulps away, nearest first; a candidate must keep every incident
// cell counter-clockwise, so the mesh stays a valid triangulation.
class Nudger {
 public:
  Nudger(const std::vector<Polygon>& region, const std::vector<const Polygon*>& obstacles,
         FreeSpaceTriangulation& out)
      : out_(out) {
    // Each polygon is asked only where its box holds the point: a street region is many
    // polygons, or one of tens of thousands of vertices (RingLocator).
    std::vector<Box2> boxes;
    for (const Polygon* p : obstacles) {
      boxes.push_back(bounds(*p));
      obstacles_.emplace_back(*p);
    }
    obstacle_grid_ = BoxGrid(boxes, 1.0);
    boxes.clear();
    for (const Polygon& r : region) {
      boxes.push_back(bounds(r));
      region_.emplace_back(r);
    }
    region_grid_ = BoxGrid(boxes, 1.0);
  }

  void run() {
    std::vector<std::size_t> bad;
    for (std::size_t v = 0; v < out_.vertices.size(); ++v)
      if (!acceptable(to_point(out_.vertices[v]))) bad.push_back(v);
    if (bad.empty()) return;
    std::vector<std::vector<std::uint32_t>> incident(out_.vertices.size());
    std::vector<char> wanted(out_.vertices.size(), 0);
    for (std::size_t v : bad) wanted[v] = 1;
    for (std::size_t t = 0; t < out_.triangles.size(); ++t)
      for (std::uint32_t v : out_.triangles[t])
        if (wanted[v]) incident[v].push_back(std::uint32_t(t));
    for (std::size_t v : bad) {
      if (nudge(v, incident[v]))
        ++out_.nudged_vertices;
      else
        ++out_.unresolved_vertices;
    }
  }

 private:
  // In the closed free space: in some region polygon (closed) and strictly inside no obstacle.
  bool acceptable(const Point& p) const {
    for (std::uint32_t i : obstacle_grid_.at({p.x(), p.y()}))
      if (obstacles_[i].strictly_inside(p)) return false;
    for (std::uint32_t i : region_grid_.at({p.x(), p.y()}))
      if (region_[i].inside_or_on(p)) return true;
    return false;
  }

  bool keeps_orientation(std::size_t v, const Point& p,
                         const std::vector<std::uint32_t>& incident) const {
    for (std::uint32_t t : incident) {
      std::array<Point, 3> c;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t w = out_.triangles[t][std::size_t(k)];
        c[std::size_t(k)] = w == v ? p : to_point(out_.vertices[w]);
      }
      if (CGAL::orientation(c[0], c[1], c[2]) != CGAL::LEFT_TURN) return false;
    }
    return true;
  }

  static double step(double x, int n) {
    const double dir = n < 0 ? -INFINITY : INFINITY;
    for (int i = 0; i < std::abs(n); ++i) x = std::nextafter(x, dir);
    return x;
  }

  bool nudge(std::size_t v, const std::vector<std::uint32_t>& incident) {
    const Vec2 p = out_.vertices[v];
    constexpr int kMaxUlps = 64;
    for (int r = 1; r <= kMaxUlps; ++r)
      for (int i = -r; i <= r; ++i)
        for (int j = -r; j <= r; ++j) {
          if (std::max(std::abs(i), std::abs(j)) != r) continue;
          const Point q(step(p.x, i), step(p.y, j));
          if (acceptable(q) && keeps_orientation(v, q, incident)) {
            out_.vertices[v] = {q.x(), q.y()};
            return true;
          }
        }
    return false;
  }

  std::vector<PolygonLocator> region_;
  std::vector<PolygonLocator> obstacles_;
  FreeSpaceTriangulation& out_;
  BoxGrid region_grid_;
  BoxGrid obstacle_grid_;
};

std::vector<Point> ring_points(const Ring& r) {
  std::vector<Point> pts;
  pts.reserve(r.size());
  for (Vec2 v : r) pts.push_back(to_point(v));
  return pts;
}

// Any orientation is accepted: a ring counts +1 inside when it is an outer ring, -1 inside when
// it is a hole, whichever way it runs.
void insert_polygon(Cdtp& cdt, const Polygon& poly, Kind kind, std::vector<CdtRing>& out) {
  auto insert_ring = [&](const Ring& r, bool hole) {
    const std::vector<Point> pts = ring_points(r);
    const Cdtp::Constraint_id id = cdt.insert_constraint(pts.begin(), pts.end(), /*close=*/true);
    const bool ccw = signed_area2(r) > 0;
    if (id != Cdtp::Constraint_id(nullptr)) out.push_back({id, kind, ccw != hole ? 1 : -1});
  };
  insert_ring(poly.outer, false);
  for (const Ring& h : poly.holes) insert_ring(h, true);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Thesis 5.3 triangulates free space as it is; real footprints add slivers of it between nearly
// coincident walls of neighbouring buildings (digitizing noise, 0.1 mm wide in the Helsinki
// data). Delaunay refinement fills a sliver with well-shaped triangles as small as its width:
// tens of thousands of useless cells. A face of the unrefined triangulation is such a sliver when
// it is thinner than `narrow_gap` and runs along a wall (one of its two long edges is
// constrained); its area is reported, not silently dropped.
bool is_sliver(Face_handle f, double narrow_gap) {
  std::array<double, 3> len{};
  std::array<Point, 3> p;
  for (int k = 0; k < 3; ++k) p[std::size_t(k)] = f->vertex(k)->point();
  for (int k = 0; k < 3; ++k)
    len[std::size_t(k)] = std::sqrt(
        CGAL::squared_distance(p[std::size_t(Cdtp::ccw(k))], p[std::size_t(Cdtp::cw(k))]));
  const int shortest = int(std::min_element(len.begin(), len.end()) - len.begin());
  const double longest = *std::max_element(len.begin(), len.end());
  const double area2 = std::abs(CGAL::area(p[0], p[1], p[2])) * 2;
  if (!(area2 < narrow_gap * longest)) return false;
  for (int k = 0; k < 3; ++k)
    if (k != shortest && f->is_constrained(k)) return true;
  return false;
}

double triangle_area(const Face_handle f) {
  return std::abs(CGAL::to_double(
      CGAL::area(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point())));
}

}  // namespace

FreeSpaceTriangulation triangulate_free_space(const std::vector<Polygon>& region,
                                              const std::vector<const Polygon*>& obstacles,
                                              double max_edge, double shape_bound, double min_edge,
                                              double narrow_gap) {
  FreeSpaceTriangulation out;
  auto t0 = std::chrono::steady_clock::now();
  Box2 region_box;
  for (const Polygon& r : region) region_box.extend(bounds(r));

  // Pass 1: the arrangement of all rings, classified by winding numbers.
  std::vector<const Polygon*> used;  // obstacles that can touch the region
  std::vector<std::pair<Point, Point>> boundary;
  {
    Cdtp all;
    std::vector<CdtRing> rings;
    for (const Polygon& r : region) insert_polygon(all, r, kRegion, rings);
    for (const Polygon* p : obstacles)
      if (bounds(*p).overlaps(region_box)) {
        insert_polygon(all, *p, kObstacle, rings);
        used.push_back(p);
      }
    out.constraint_vertices = all.number_of_vertices();
    classify(all, rings);
    for (Face_handle f : all.finite_face_handles()) {
      f->set_in_domain(is_free(all, f));
      if (f->is_in_domain() && narrow_gap > 0 && is_sliver(f, narrow_gap)) {
        f->set_in_domain(false);
        out.sliver_area += triangle_area(f);
        ++out.sliver_faces;
      }
    }
    all.infinite_face()->set_in_domain(false);
    // Only the boundary of the domain is kept: shared walls, overlaps and sliver edges inside
    // buildings would otherwise be refined too (the mesher splits every encroached constraint).
    for (Face_handle f : all.finite_face_handles())
      if (f->is_in_domain())
        for (int i = 0; i < 3; ++i)
          if (!f->neighbor(i)->is_in_domain())  // f lies left of ccw(i) -> cw(i)
            boundary.emplace_back(f->vertex(Cdtp::ccw(i))->point(),
                                  f->vertex(Cdtp::cw(i))->point());
  }

  // Pass 2: the domain's boundary alone, each edge with the domain on its left.
  Cdtp cdt;
  std::vector<CdtRing> rings;
  rings.reserve(boundary.size());
  for (const auto& [a, b] : boundary)
    if (const Cdtp::Constraint_id id = cdt.insert_constraint(a, b);
        id != Cdtp::Constraint_id(nullptr))
      rings.push_back({id, kRegion});
  classify(cdt, rings);
  out.seconds_cdt = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  for (Face_handle f : cdt.all_face_handles()) f->set_in_domain(is_free(cdt, f));
  {
    const ScopedWallFloor floor(min_edge);
    Mesher mesher(cdt, CellCriteria(shape_bound, max_edge, min_edge));
    mesher.refine_mesh();
  }
  // The mesher split constrained edges; the hierarchy followed, so classify again from scratch
  // rather than trusting the mesher's own marks.
  classify(cdt, rings);
  for (Vertex_handle v : cdt.finite_vertex_handles()) v->info() = -1;
  for (Face_handle f : cdt.finite_face_handles()) {
    if (!is_free(cdt, f)) continue;
    f->info().index = std::int32_t(out.triangles.size());
    std::array<std::uint32_t, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const Vertex_handle v = f->vertex(k);
      if (v->info() < 0) {
        v->info() = std::int32_t(out.vertices.size());
        out.vertices.push_back({v->point().x(), v->point().y()});
      }
      tri[std::size_t(k)] = std::uint32_t(v->info());
    }
    out.triangles.push_back(tri);
  }
  out.neighbours.reserve(out.triangles.size());
  for (Face_handle f : cdt.finite_face_handles()) {
    if (f->info().index < 0) continue;
    std::array<std::int32_t, 3> nb{};
    for (int k = 0; k < 3; ++k) nb[std::size_t(k)] = f->neighbor(k)->info().index;
    out.neighbours.push_back(nb);
  }
  Nudger(region, used, out).run();
  out.seconds_refine = seconds_since(t0);
  return out;
}

}  // namespace urbanpvs::geometry::detail
