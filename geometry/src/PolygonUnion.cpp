// SPDX-License-Identifier: GPL-3.0-or-later
// Kept in its own translation unit: CGAL's Boolean set operations with exact constructions take
// ~26 s and 1.4 GB to compile.
#include "urbanpvs/geometry/PolygonUnion.hpp"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_set_2.h>

namespace urbanpvs::geometry {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalPolygon = CGAL::Polygon_2<K>;
using CgalPolygonWithHoles = CGAL::Polygon_with_holes_2<K>;

CgalPolygon to_cgal(const Ring& r) {
  CgalPolygon p;
  for (Vec2 v : r) p.push_back(K::Point_2(v.x, v.y));
  return p;
}

// Drops vertices on the straight line through their neighbours, decided exactly: the join keeps
// the endpoints of every shared wall (NOTES.md), which would otherwise become tiny occluder edges.
Ring simplified(const CgalPolygon& p) {
  std::vector<K::Point_2> pts(p.vertices_begin(), p.vertices_end());
  bool changed = true;
  while (changed && pts.size() > 3) {
    changed = false;
    for (std::size_t i = 0; i < pts.size() && pts.size() > 3; ++i) {
      const auto& a = pts[(i + pts.size() - 1) % pts.size()];
      const auto& b = pts[i];
      const auto& c = pts[(i + 1) % pts.size()];
      if (a == b || CGAL::collinear(a, b, c)) {
        pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        --i;
      }
    }
  }
  Ring r;
  r.reserve(pts.size());
  for (const auto& v : pts) r.push_back({CGAL::to_double(v.x()), CGAL::to_double(v.y())});
  return r;
}

}  // namespace

std::vector<Polygon> union_polygons(const std::vector<Polygon>& polys) {
  std::vector<CgalPolygonWithHoles> in;
  in.reserve(polys.size());
  for (const Polygon& poly : polys) {
    CgalPolygonWithHoles p(to_cgal(poly.outer));
    for (const Ring& h : poly.holes) p.add_hole(to_cgal(h));
    in.push_back(std::move(p));
  }
  CGAL::Polygon_set_2<K> set;
  set.join(in.begin(), in.end());

  std::vector<CgalPolygonWithHoles> result;
  set.polygons_with_holes(std::back_inserter(result));
  std::vector<Polygon> out;
  out.reserve(result.size());
  for (const CgalPolygonWithHoles& p : result) {
    Polygon poly{simplified(p.outer_boundary()), {}};
    if (signed_area2(poly.outer) < 0) std::reverse(poly.outer.begin(), poly.outer.end());
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h) {
      Ring hole = simplified(*h);
      if (signed_area2(hole) > 0) std::reverse(hole.begin(), hole.end());
      poly.holes.push_back(std::move(hole));
    }
    out.push_back(std::move(poly));
  }
  return out;
}

}  // namespace urbanpvs::geometry
