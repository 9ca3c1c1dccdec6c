// SPDX-License-Identifier: GPL-3.0-or-later
#include "FaceTriangulation.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <cstddef>
#include <deque>
#include <limits>
#include <set>
#include <utility>

namespace urbanpvs::geometry {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
/// Each face's nesting: 0 outside every ring, 1 inside the outer ring, 2 inside a hole, ...
using Fb =
    CGAL::Constrained_triangulation_face_base_2<K,
                                                CGAL::Triangulation_face_base_with_info_2<int, K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact predicates with intersections: rings that cross get a vertex at the crossing, which
// has no index (-1) and so shows that the face is not a polygon with holes.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

}  // namespace

bool triangulate_face(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& rings,
                      std::vector<std::array<int, 3>>& out) {
  return triangulate_face(points, rings, {}, out);
}

bool triangulate_face(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& rings,
                      const std::vector<std::pair<int, int>>& cuts,
                      std::vector<std::array<int, 3>>& out) {
  if (rings.empty() || rings.front().size() < 3) return false;
  const std::vector<int>& outer = rings.front();
  const int drop = dominant_axis(newell_normal(
      outer.size(), [&](std::size_t k) { return points[static_cast<std::size_t>(outer[k])]; }));
  Cdt cdt;
  std::size_t inserted = 0;  // distinct vertices of the rings and the cuts
  bool folds = false;
  auto vertex = [&](int index) {
    const Vec2 p = planar(points[static_cast<std::size_t>(index)], drop);
    const K::Point_2 q(p.x, p.y);
    const std::size_t before = cdt.number_of_vertices();
    Cdt::Vertex_handle v = cdt.insert(q);
    if (cdt.number_of_vertices() > before) {
      ++inserted;
      v->info() = index;
    } else if (v->info() != index) {
      folds = true;  // two corners on one point of the plane: the face folds over itself
    }
    return v;
  };
  std::set<std::pair<int, int>> ring_edges;  // by index, the smaller first
  std::vector<std::pair<Cdt::Vertex_handle, Cdt::Vertex_handle>> ring_handles;
  for (const std::vector<int>& ring : rings) {
    std::vector<Cdt::Vertex_handle> handles;
    for (const int index : ring) handles.push_back(vertex(index));
    if (folds) return false;
    for (std::size_t k = 0; k < handles.size(); ++k) {
      const Cdt::Vertex_handle a = handles[k], b = handles[(k + 1) % handles.size()];
      if (a == b) continue;
      cdt.insert_constraint(a, b);
      ring_edges.insert(std::minmax(a->info(), b->info()));
      ring_handles.emplace_back(a, b);
    }
  }
  for (const auto& [from, to] : cuts) {
    const Cdt::Vertex_handle a = vertex(from), b = vertex(to);
    if (folds) return false;
    if (a != b) cdt.insert_constraint(a, b);
  }
  // A vertex that no ring or cut gave is where two constraints cross.
  if (cdt.dimension() < 2 || cdt.number_of_vertices() != inserted) return false;
  // Crossing a ring's edge goes one ring deeper, crossing a cut does not: so every ring's edge
  // must be an edge of the triangulation (a cut's end on it would split it).
  if (!cuts.empty())
    for (const auto& [a, b] : ring_handles)
      if (!cdt.is_edge(a, b)) return false;
  auto deeper = [&](Cdt::Face_handle f, int e) {
    if (!f->is_constrained(e)) return 0;
    if (cuts.empty()) return 1;
    const int u = f->vertex(Cdt::cw(e))->info(), v = f->vertex(Cdt::ccw(e))->info();
    return ring_edges.contains(std::minmax(u, v)) ? 1 : 0;
  };
  // Nesting by a walk from the outside (a 0-1 breadth-first search).
  constexpr int kUnknown = std::numeric_limits<int>::max();
  for (Cdt::Face_handle f : cdt.all_face_handles()) f->info() = kUnknown;
  std::deque<Cdt::Face_handle> queue = {cdt.infinite_face()};
  cdt.infinite_face()->info() = 0;
  while (!queue.empty()) {
    const Cdt::Face_handle f = queue.front();
    queue.pop_front();
    for (int e = 0; e < 3; ++e) {
      const Cdt::Face_handle g = f->neighbor(e);
      const int step = deeper(f, e);
      if (g->info() <= f->info() + step) continue;
      g->info() = f->info() + step;
      if (step)
        queue.push_back(g);
      else
        queue.push_front(g);
    }
  }
  const std::size_t before = out.size();
  for (Cdt::Face_handle f : cdt.finite_face_handles())
    if (f->info() % 2 == 1)
      out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return out.size() > before;
}

}  // namespace urbanpvs::geometry
