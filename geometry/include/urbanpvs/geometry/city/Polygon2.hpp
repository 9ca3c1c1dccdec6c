// SPDX-License-Identifier: GPL-3.0-or-later
// Plain 2D polygon types shared by every stage. They carry doubles only: CGAL's exact kernels
// live inside the .cpp files that need them (see PolygonUnion.hpp, PolygonOffset.hpp), so code
// that only passes polygons around compiles fast.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "urbanpvs/geometry/city/Vector.hpp"

namespace urbanpvs::geometry {

/// An open ring: the closing edge from back() to front() is implied, no point is repeated.
using Ring = std::vector<Vec2>;

/// A polygon with holes. Invariant after input cleanup: outer is counter-clockwise, holes are
/// clockwise, every ring has >= 3 points and no self-intersection.
struct Polygon {
  Ring outer;
  std::vector<Ring> holes;
};

struct Box2 {
  Vec2 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};

  bool empty() const { return min.x > max.x; }
  void extend(Vec2 p) {
    min = {std::min(min.x, p.x), std::min(min.y, p.y)};
    max = {std::max(max.x, p.x), std::max(max.y, p.y)};
  }
  void extend(const Box2& b) {
    if (!b.empty()) {
      extend(b.min);
      extend(b.max);
    }
  }
  bool overlaps(const Box2& b) const {
    return min.x <= b.max.x && b.min.x <= max.x && min.y <= b.max.y && b.min.y <= max.y;
  }
  Box2 grown(double d) const { return {{min.x - d, min.y - d}, {max.x + d, max.y + d}}; }
  /// The four corners, counter-clockwise from min (a non-empty box).
  Ring corners() const { return {min, {max.x, min.y}, max, {min.x, max.y}}; }
  double area() const { return empty() ? 0.0 : (max.x - min.x) * (max.y - min.y); }
};

/// The parameters [*t0, *t1] within [0, t_max] at which the line from + t·d lies in `box`
/// (slab method); false when it misses. t_max = infinity for a ray.
inline bool clip_line_to_box(Vec2 from, Vec2 d, const Box2& box, double t_max, double* t0,
                             double* t1) {
  *t0 = 0;
  *t1 = t_max;
  auto slab = [&](double o, double dv, double lo, double hi) {
    if (dv == 0) return lo <= o && o <= hi;
    double a = (lo - o) / dv, b = (hi - o) / dv;
    if (a > b) std::swap(a, b);
    *t0 = std::max(*t0, a);
    *t1 = std::min(*t1, b);
    return *t0 <= *t1;
  };
  return slab(from.x, d.x, box.min.x, box.max.x) && slab(from.y, d.y, box.min.y, box.max.y);
}

struct Box3 {
  Box2 xy;
  double zmin = std::numeric_limits<double>::infinity();
  double zmax = -std::numeric_limits<double>::infinity();

  void extend(Vec2 p, double z) {
    xy.extend(p);
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  void extend(const Box3& b) {
    xy.extend(b.xy);
    zmin = std::min(zmin, b.zmin);
    zmax = std::max(zmax, b.zmax);
  }
};

/// Twice the signed area: positive for counter-clockwise rings.
inline double signed_area2(const Ring& r) {
  double a = 0;
  for (std::size_t i = 0, n = r.size(); i < n; ++i) a += cross(r[i], r[(i + 1) % n]);
  return a;
}

inline double area(const Polygon& p) {
  double a = std::abs(signed_area2(p.outer));
  for (const Ring& h : p.holes) a -= std::abs(signed_area2(h));
  return 0.5 * a;
}

inline Box2 bounds(const Ring& r) {
  Box2 b;
  for (Vec2 p : r) b.extend(p);
  return b;
}

inline Box2 bounds(const Polygon& p) {
  return bounds(p.outer);
}

/// Even-odd point-in-ring test; points exactly on the boundary may go either way.
inline bool inside_ring(const Ring& r, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
    const Vec2 a = r[i], b = r[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

inline bool inside(const Polygon& poly, Vec2 p) {
  if (!inside_ring(poly.outer, p)) return false;
  return std::none_of(poly.holes.begin(), poly.holes.end(),
                      [&](const Ring& h) { return inside_ring(h, p); });
}

/// Euclidean distance from p to the segment ab.
inline double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  double t = len2 > 0 ? dot(p - a, ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const Vec2 q = a + t * ab;
  return std::hypot(p.x - q.x, p.y - q.y);
}

/// Calls f(a, b) for every edge of every ring of the polygon.
template <class F>
void for_each_edge(const Polygon& poly, F&& f) {
  auto ring_edges = [&](const Ring& r) {
    for (std::size_t i = 0, n = r.size(); i < n; ++i) f(r[i], r[(i + 1) % n]);
  };
  ring_edges(poly.outer);
  for (const Ring& h : poly.holes) ring_edges(h);
}

}  // namespace urbanpvs::geometry
