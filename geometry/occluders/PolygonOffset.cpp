// SPDX-License-Identifier: GPL-3.0-or-later
// Kept in its own translation unit: CGAL's straight skeleton takes ~17 s and 1 GB to compile.
#include "urbanpvs/geometry/occluders/PolygonOffset.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/create_offset_polygons_from_polygon_with_holes_2.h>

namespace urbanpvs::geometry {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalPolygon = CGAL::Polygon_2<K>;
using CgalPolygonWithHoles = CGAL::Polygon_with_holes_2<K>;

CgalPolygon to_cgal(const Ring& r) {
  CgalPolygon p;
  for (Vec2 v : r) p.push_back(K::Point_2(v.x, v.y));
  return p;
}

CgalPolygonWithHoles to_cgal(const Polygon& poly) {
  CgalPolygonWithHoles p(to_cgal(poly.outer));
  for (const Ring& h : poly.holes) p.add_hole(to_cgal(h));
  return p;
}

Ring from_cgal(const CgalPolygon& p) {
  Ring r;
  r.reserve(p.size());
  for (const auto& v : p.container()) r.push_back({v.x(), v.y()});
  return r;
}

template <class PtrRange>
std::vector<Polygon> from_cgal(const PtrRange& result) {
  std::vector<Polygon> out;
  for (const auto& pwh : result) {
    if (pwh->outer_boundary().size() < 3) continue;
    Polygon poly{from_cgal(pwh->outer_boundary()), {}};
    if (signed_area2(poly.outer) < 0) std::reverse(poly.outer.begin(), poly.outer.end());
    for (auto h = pwh->holes_begin(); h != pwh->holes_end(); ++h) {
      Ring hole = from_cgal(*h);
      if (hole.size() < 3) continue;
      if (signed_area2(hole) > 0) std::reverse(hole.begin(), hole.end());
      poly.holes.push_back(std::move(hole));
    }
    out.push_back(std::move(poly));
  }
  return out;
}

}  // namespace

// The straight skeleton can fail on nearly degenerate input (it then throws or returns pieces
// that are not inside the input). An occluder may always be dropped without breaking the
// conservative contract, so any piece that does not lie inside the input is discarded.
std::vector<Polygon> shrink_polygon(const Polygon& poly, double d) {
  if (!(d > 0)) return {poly};
  std::vector<Polygon> pieces;
  try {
    // Empty when the whole polygon vanishes (CGAL's offset returns nothing then).
    pieces = from_cgal(
        CGAL::create_interior_skeleton_and_offset_polygons_with_holes_2(d, to_cgal(poly)));
  } catch (const std::exception&) {
    return {};
  }
  std::erase_if(pieces, [&](const Polygon& p) {
    return !std::all_of(p.outer.begin(), p.outer.end(), [&](Vec2 v) { return inside(poly, v); });
  });
  return pieces;
}

std::vector<Polygon> grow_polygon(const Polygon& poly, double d) {
  if (!(d > 0)) return {poly};
  return from_cgal(
      CGAL::create_exterior_skeleton_and_offset_polygons_with_holes_2(d, to_cgal(poly)));
}

}  // namespace urbanpvs::geometry
