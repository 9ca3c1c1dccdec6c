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
  if (rings.empty() || rings.front().size() < 3) return false;
  const std::vector<int>& outer = rings.front();
  const Vec3 a = glm::abs(newell_normal(
      outer.size(), [&](std::size_t k) { return points[static_cast<std::size_t>(outer[k])]; }));
  const int drop = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  Cdt cdt;
  std::size_t inserted = 0;  // distinct vertices of the rings
  for (const std::vector<int>& ring : rings) {
    std::vector<Cdt::Vertex_handle> handles;
    for (const int index : ring) {
      const Vec3& p = points[static_cast<std::size_t>(index)];
      const K::Point_2 q = drop == 0   ? K::Point_2(p.y, p.z)
                           : drop == 1 ? K::Point_2(p.z, p.x)
                                       : K::Point_2(p.x, p.y);
      const std::size_t before = cdt.number_of_vertices();
      Cdt::Vertex_handle v = cdt.insert(q);
      if (cdt.number_of_vertices() > before) {
        ++inserted;
        v->info() = index;
      } else if (v->info() != index) {
        return false;  // two corners on one point of the plane: the face folds over itself
      }
      handles.push_back(v);
    }
    for (std::size_t k = 0; k < handles.size(); ++k)
      if (handles[k] != handles[(k + 1) % handles.size()])
        cdt.insert_constraint(handles[k], handles[(k + 1) % handles.size()]);
  }
  // A vertex that no ring gave is where two constraints cross.
  if (cdt.dimension() < 2 || cdt.number_of_vertices() != inserted) return false;
  // Nesting by a walk from the outside (a 0-1 breadth-first search): crossing a constrained
  // edge goes one ring deeper.
  constexpr int kUnknown = std::numeric_limits<int>::max();
  for (Cdt::Face_handle f : cdt.all_face_handles()) f->info() = kUnknown;
  std::deque<Cdt::Face_handle> queue = {cdt.infinite_face()};
  cdt.infinite_face()->info() = 0;
  while (!queue.empty()) {
    const Cdt::Face_handle f = queue.front();
    queue.pop_front();
    for (int e = 0; e < 3; ++e) {
      const Cdt::Face_handle g = f->neighbor(e);
      const int deeper = f->is_constrained(e) ? 1 : 0;
      if (g->info() <= f->info() + deeper) continue;
      g->info() = f->info() + deeper;
      if (deeper)
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
