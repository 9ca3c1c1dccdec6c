// SPDX-License-Identifier: GPL-3.0-or-later
// Repairs polygons whose rings are not simple (self-intersections, bow-ties, spikes, holes that
// cross or leave their outer ring) into valid polygons, the way a renderer fills them: the
// region where the outer ring winds non-zero and no hole does. Real data has such rings (one in
// the 3D BAG tile, two in a municipal LoD2 model); refusing the whole city for them is no help.
// Kept in its own translation unit: it instantiates CGAL's constrained triangulation.
#include "RingRepair.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>

#include "WindingNumbers.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry::detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  std::array<int, 2> winding{};
  bool seen = false;
};
using Vb = CGAL::Triangulation_vertex_base_2<K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<
    K, CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact predicates with intersections: the crossings of a self-intersecting ring become
// vertices, so every face lies wholly inside or wholly outside each ring.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Cdtp = CGAL::Constrained_triangulation_plus_2<Cdt>;

constexpr int kOuter = 0;
constexpr int kHole = 1;

}  // namespace

std::vector<Polygon> fill_by_winding(const std::vector<Ring>& rings) {
  if (rings.empty()) return {};
  Cdtp cdt;
  std::vector<RingConstraint<Cdtp>> constraints;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    if (rings[i].size() < 3) continue;
    std::vector<K::Point_2> pts;
    pts.reserve(rings[i].size());
    for (Vec2 v : rings[i]) pts.emplace_back(v.x, v.y);
    const auto id = cdt.insert_constraint(pts.begin(), pts.end(), /*close=*/true);
    if (id == Cdtp::Constraint_id(nullptr)) continue;
    // The sign only decides whether a lobe winds +1 or -1; non-zero is inside either way.
    constraints.push_back({id, i == 0 ? kOuter : kHole, signed_area2(rings[i]) >= 0 ? 1 : -1});
  }
  if (cdt.dimension() < 2) return {};  // every point on one line: no area at all
  classify_windings(cdt, constraints);
  std::vector<Polygon> triangles;
  for (Cdtp::Face_handle f : cdt.finite_face_handles()) {
    if (f->info().winding[kOuter] == 0 || f->info().winding[kHole] != 0) continue;
    Ring t;
    for (int k = 0; k < 3; ++k) t.push_back({f->vertex(k)->point().x(), f->vertex(k)->point().y()});
    if (signed_area2(t) <= 0) continue;  // collinear points rounded flat: no area to keep
    triangles.push_back({std::move(t), {}});
  }
  if (triangles.empty()) return {};
  std::vector<Polygon> merged = union_polygons(triangles);
  // On tangled input the union's rings may still meet where rounding put them; the triangles
  // themselves are always valid, disjoint pieces of the same region.
  for (const Polygon& p : merged)
    if (!polygon_defect(p).empty()) return triangles;
  return merged;
}

}  // namespace urbanpvs::geometry::detail
