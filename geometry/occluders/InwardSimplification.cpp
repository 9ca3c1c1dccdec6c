// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/occluders/InwardSimplification.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace urbanpvs::geometry {
namespace {

// Whether p lies in the closed triangle a, b, c (either orientation, degenerate ones included:
// then every point on their line counts, which only keeps more corners).
bool in_closed_triangle(Vec2 a, Vec2 b, Vec2 c, Vec2 p) {
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  const bool negative = d1 < 0 || d2 < 0 || d3 < 0;
  const bool positive = d1 > 0 || d2 > 0 || d3 > 0;
  return !(negative && positive);
}

}  // namespace

Polygon simplified_inward(const Polygon& polygon, double tolerance) {
  if (!(tolerance >= 0)) return polygon;
  std::vector<const Ring*> input{&polygon.outer};
  for (const Ring& h : polygon.holes) input.push_back(&h);
  // Every vertex once, rings as lists of their vertices' numbers; a cut vertex stays in the
  // x-sorted list, marked, so the test for vertices inside a cut is a binary search away.
  std::vector<Vec2> point;
  std::vector<std::vector<std::uint32_t>> rings(input.size());
  std::vector<std::uint32_t> first(input.size());  // ring r's numbers: first[r], first[r] + 1, ...
  for (std::size_t r = 0; r < input.size(); ++r) {
    first[r] = static_cast<std::uint32_t>(point.size());
    for (Vec2 p : *input[r]) {
      rings[r].push_back(static_cast<std::uint32_t>(point.size()));
      point.push_back(p);
    }
  }
  // Whether every input vertex of ring r strictly between ia and ib (the corner and those cut
  // before it there) lies within the tolerance of the line through them: then so does the
  // whole stretch of input boundary the chord replaces. A chord replaces at most kMaxSpan of
  // them: that bounds the work of a cut, which would otherwise grow with the length of a
  // straight wall of many vertices (50,000 on one wall took seconds), and costs nothing on real
  // outlines, whose cuts within a metre span a few vertices.
  constexpr std::uint32_t kMaxSpan = 64;
  auto within_tolerance = [&](std::size_t r, std::uint32_t ia, std::uint32_t ib) {
    const std::uint32_t n = static_cast<std::uint32_t>(input[r]->size());
    const Vec2 a = point[ia], b = point[ib];
    const double chord = std::hypot(b.x - a.x, b.y - a.y);
    if (!(chord > 0) || (ib + n - ia) % n > kMaxSpan + 1) return false;
    for (std::uint32_t k = (ia - first[r] + 1) % n + first[r]; k != ib;
         k = (k - first[r] + 1) % n + first[r])
      if (std::abs(cross(b - a, point[k] - a)) > tolerance * chord) return false;
    return true;
  };
  std::vector<char> alive(point.size(), 1);
  std::vector<std::uint32_t> by_x(point.size());
  for (std::uint32_t k = 0; k < by_x.size(); ++k) by_x[k] = k;
  std::sort(by_x.begin(), by_x.end(),
            [&](std::uint32_t a, std::uint32_t b) { return point[a].x < point[b].x; });
  // The solid lies left of every edge when the outer ring turns counter-clockwise and the holes
  // clockwise; a ring the other way round is read reversed, so a cut never grows the solid.
  std::vector<double> side;
  for (std::size_t r = 0; r < input.size(); ++r)
    side.push_back((signed_area2(*input[r]) > 0) == (r == 0) ? 1.0 : -1.0);
  // A vertex other than the corner's own three inside the triangle the cut would remove: the
  // chord would cross or touch the boundary there.
  auto blocked = [&](std::uint32_t ia, std::uint32_t iv, std::uint32_t ib) {
    const Vec2 a = point[ia], v = point[iv], b = point[ib];
    const double x0 = std::min({a.x, v.x, b.x}), x1 = std::max({a.x, v.x, b.x});
    auto k = std::lower_bound(by_x.begin(), by_x.end(), x0,
                              [&](std::uint32_t q, double x) { return point[q].x < x; });
    for (; k != by_x.end() && point[*k].x <= x1; ++k) {
      const std::uint32_t q = *k;
      if (!alive[q] || q == ia || q == iv || q == ib) continue;
      if (in_closed_triangle(a, v, b, point[q])) return true;
    }
    return false;
  };
  // Passes until nothing changes: each cut may make its neighbours cuttable.
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t r = 0; r < rings.size(); ++r) {
      std::vector<std::uint32_t>& ring = rings[r];
      for (std::size_t i = 0; i < ring.size() && ring.size() > 3;) {
        const std::size_t n = ring.size();
        const std::uint32_t ia = ring[(i + n - 1) % n], iv = ring[i], ib = ring[(i + 1) % n];
        const Vec2 a = point[ia], v = point[iv], b = point[ib];
        // A convex (or straight) corner of the solid: the chord runs inside.
        const bool convex = side[r] * cross(v - a, b - v) >= 0;
        if (convex && within_tolerance(r, ia, ib) && !blocked(ia, iv, ib)) {
          alive[iv] = 0;
          ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
          changed = true;
        } else {
          ++i;
        }
      }
    }
  }
  Polygon out;
  auto ring_of = [&](const std::vector<std::uint32_t>& ids) {
    Ring ring;
    for (std::uint32_t k : ids) ring.push_back(point[k]);
    return ring;
  };
  out.outer = ring_of(rings[0]);
  for (std::size_t r = 1; r < rings.size(); ++r) out.holes.push_back(ring_of(rings[r]));
  return out;
}

}  // namespace urbanpvs::geometry
