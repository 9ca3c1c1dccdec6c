// SPDX-License-Identifier: GPL-3.0-or-later
// Vertex removal with an empty-triangle test. Removing vertex v between its neighbours a and b
// replaces edges a-v, v-b by a-b. No other ring edge can cross a-b unless it also crosses a-v
// or v-b (impossible: the rings are valid) or ends inside the triangle a, v, b; so when no other
// live vertex lies in the closed triangle, the rings stay simple and disjoint. (CGAL's
// Polyline_simplification_2 crashed on rings that come within 1 µm of each other, as the exact
// union returns them where buildings touch at a corner.)
#include "BoundarySimplification.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "BoxGrid.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"

namespace urbanpvs::geometry::detail {
namespace {

struct Vertex {
  Vec2 p;
  std::uint32_t ring = 0;
  std::uint32_t prev = 0, next = 0;  // live neighbours in the ring (indices into vertices)
  bool alive = true;
  // Original points removed on the edge from this vertex to `next`: the new boundary must stay
  // within the tolerance of every one of them.
  std::vector<Vec2> dropped;
};

bool in_closed_triangle(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  const bool neg = d1 < 0 || d2 < 0 || d3<0, pos = d1> 0 || d2 > 0 || d3 > 0;
  return !(neg && pos);
}

}  // namespace

std::vector<Polygon> simplify_boundaries(const std::vector<Polygon>& polys, double tolerance) {
  if (!(tolerance > 0) || polys.empty()) return polys;
  std::vector<Vertex> vs;
  std::vector<std::uint32_t> ring_first, ring_size, ring_polygon;
  auto add_ring = [&](const Ring& r, std::uint32_t polygon) {
    const auto first = static_cast<std::uint32_t>(vs.size());
    const auto ring = static_cast<std::uint32_t>(ring_first.size());
    const auto n = static_cast<std::uint32_t>(r.size());
    for (std::uint32_t k = 0; k < n; ++k)
      vs.push_back({r[k], ring, first + (k + n - 1) % n, first + (k + 1) % n, true, {}});
    ring_first.push_back(first);
    ring_size.push_back(n);
    ring_polygon.push_back(polygon);
  };
  for (std::uint32_t i = 0; i < polys.size(); ++i) {
    add_ring(polys[i].outer, i);
    for (const Ring& h : polys[i].holes) add_ring(h, i);
  }
  std::vector<Box2> points(vs.size());
  for (std::size_t i = 0; i < vs.size(); ++i) points[i].extend(vs[i].p);
  const BoxGrid grid(points, 4.0);

  auto removable = [&](std::uint32_t v) {
    const Vertex& x = vs[v];
    if (ring_size[x.ring] <= 3) return false;
    const Vec2 a = vs[x.prev].p, b = vs[x.next].p;
    // Every original point between a and b, v included, within the tolerance of a-b.
    auto near = [&](Vec2 q) { return distance_to_segment(q, a, b) <= tolerance; };
    if (!near(x.p)) return false;
    for (Vec2 q : vs[x.prev].dropped)
      if (!near(q)) return false;
    for (Vec2 q : x.dropped)
      if (!near(q)) return false;
    Box2 box;
    for (Vec2 q : {a, b, x.p}) box.extend(q);
    for (std::int64_t gy = grid.clamp_y(box.min.y); gy <= grid.clamp_y(box.max.y); ++gy)
      for (std::int64_t gx = grid.clamp_x(box.min.x); gx <= grid.clamp_x(box.max.x); ++gx)
        for (std::uint32_t w : grid.bucket(gx, gy))
          if (w != v && w != x.prev && w != x.next && vs[w].alive &&
              in_closed_triangle(vs[w].p, a, x.p, b))
            return false;
    return true;
  };

  for (bool changed = true; changed;) {
    changed = false;
    for (std::uint32_t v = 0; v < vs.size(); ++v) {
      if (!vs[v].alive || !removable(v)) continue;
      Vertex& x = vs[v];
      Vertex& a = vs[x.prev];
      a.dropped.push_back(x.p);
      a.dropped.insert(a.dropped.end(), x.dropped.begin(), x.dropped.end());
      a.next = x.next;
      vs[x.next].prev = x.prev;
      x.alive = false;
      --ring_size[x.ring];
      changed = true;
    }
  }

  std::vector<Polygon> out(polys.size());
  std::vector<Ring> rings(ring_first.size());
  for (std::uint32_t r = 0; r < ring_first.size(); ++r) {
    std::uint32_t start = ring_first[r];
    while (!vs[start].alive) ++start;  // some vertex of the ring is alive (at least 3 are)
    std::uint32_t v = start;
    do {
      rings[r].push_back(vs[v].p);
      v = vs[v].next;
    } while (v != start);
  }
  std::uint32_t r = 0;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    Polygon p;
    p.outer = std::move(rings[r++]);
    for (std::size_t h = 0; h < polys[i].holes.size(); ++h)
      p.holes.push_back(std::move(rings[r++]));
    // The empty-triangle test keeps rings simple; the orientation check guards against a ring
    // flattened to a sliver by the tolerance.
    bool ok = signed_area2(p.outer) > 0;
    for (const Ring& h : p.holes) ok = ok && signed_area2(h) < 0;
    out[i] = ok && polygon_defect(p).empty() ? std::move(p) : polys[i];
  }
  return out;
}

}  // namespace urbanpvs::geometry::detail
