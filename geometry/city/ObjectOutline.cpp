// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/ObjectOutline.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <iterator>
#include <vector>

namespace urbanpvs::geometry {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Ring box_rectangle(const Box2& b) {
  return b.empty() ? Ring{} : b.corners();
}

}  // namespace

Ring convex_hull(const std::vector<Vec2>& points) {
  std::vector<Kernel::Point_2> in;
  in.reserve(points.size());
  for (const Vec2& p : points) in.emplace_back(p.x, p.y);
  // Exact predicates and no constructed coordinates: the hull's vertices are input points.
  std::vector<Kernel::Point_2> hull;
  CGAL::convex_hull_2(in.begin(), in.end(), std::back_inserter(hull));
  if (hull.size() < 3) return {};  // no area: a line, a point or nothing
  Ring out;
  out.reserve(hull.size());
  for (const Kernel::Point_2& p : hull) out.push_back({p.x(), p.y()});
  return out;
}

Ring object_outline(const CityObject& o) {
  return o.occludes ? object_hull(o) : box_rectangle(o.bbox.xy);
}

Ring object_hull(const CityObject& o) {
  std::vector<Vec2> points;
  for (const Surface3& s : o.surfaces)
    for (const auto& ring : s.rings)
      for (const Vec3& v : ring) points.push_back({v.x, v.y});
  for (const Polygon& p : o.footprint) points.insert(points.end(), p.outer.begin(), p.outer.end());
  for (const OccluderPrism& p : o.occluders)
    points.insert(points.end(), p.footprint.outer.begin(), p.footprint.outer.end());
  Ring out = convex_hull(points);
  if (out.empty()) return box_rectangle(o.bbox.xy);
  Box2 extent;
  for (const Vec2& v : out) extent.extend(v);
  // The box may hold geometry the surfaces do not (a ring the reader could not use): then the
  // hull does not account for all of the object, and the box decides.
  constexpr double kSlack = 1e-6;  // m: rounding between the box and the points it came from
  const Box2& b = o.bbox.xy;
  if (b.min.x < extent.min.x - kSlack || b.min.y < extent.min.y - kSlack ||
      b.max.x > extent.max.x + kSlack || b.max.y > extent.max.y + kSlack) {
    return box_rectangle(b);
  }
  return out;
}

}  // namespace urbanpvs::geometry
