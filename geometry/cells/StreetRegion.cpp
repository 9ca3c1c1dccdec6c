// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/cells/StreetRegion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "BoundarySimplification.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry {
namespace {

// How far a simplified centre line may stray from the mapped one, and how far the fused
// outline from the buffers: the region only says where cells go. [m]
constexpr double kLineTolerance = 0.5;
constexpr double kOutlineTolerance = 0.5;
// Narrower strips would only multiply cells (a well-shaped triangle in a 2 m strip has edges
// of a few metres): every line is buffered to at least this width. [m]
constexpr double kMinWidth = 6.0;

// Douglas-Peucker: the endpoints and every vertex farther than `tol` from the chord between the
// kept neighbours.
void keep_far(const std::vector<Vec2>& pts, std::size_t a, std::size_t b, double tol,
              std::vector<bool>& keep) {
  if (b <= a + 1) return;
  std::size_t far = a;
  double worst = tol;
  for (std::size_t k = a + 1; k < b; ++k)
    if (const double d = distance_to_segment(pts[k], pts[a], pts[b]); d > worst) worst = d, far = k;
  if (far == a) return;
  keep[far] = true;
  keep_far(pts, a, far, tol, keep);
  keep_far(pts, far, b, tol, keep);
}

std::vector<Vec2> simplified(const std::vector<Vec2>& pts) {
  if (pts.size() <= 2) return pts;
  std::vector<bool> keep(pts.size(), false);
  keep.front() = keep.back() = true;
  keep_far(pts, 0, pts.size() - 1, kLineTolerance, keep);
  std::vector<Vec2> out;
  for (std::size_t k = 0; k < pts.size(); ++k)
    if (keep[k]) out.push_back(pts[k]);
  return out;
}

// The octagon whose sides are `half` from its centre: a segment's rectangle meets it flush, so
// the outline has no step there for the simplification to cut across.
Polygon octagon(Vec2 c, double half) {
  const double r = half / std::cos(std::numbers::pi / 8);
  Polygon p;
  for (int k = 0; k < 8; ++k) {
    const double a = (k + 0.5) * std::numbers::pi / 4;
    p.outer.push_back(c + r * Vec2{std::cos(a), std::sin(a)});
  }
  return p;
}

void add_buffered(const std::vector<Vec2>& line, double half, std::vector<Polygon>& out) {
  for (std::size_t k = 0; k < line.size(); ++k) {
    out.push_back(octagon(line[k], half));
    if (k + 1 == line.size()) break;
    const Vec2 a = line[k], b = line[k + 1], d = b - a;
    const double len = std::hypot(d.x, d.y);
    if (!(len > 1e-6)) continue;
    const Vec2 n = (half / len) * Vec2{-d.y, d.x};
    out.push_back(Polygon{{a - n, b - n, b + n, a + n}, {}});
  }
}

}  // namespace

std::vector<Polygon> street_region(const StreetNetwork& streets) {
  std::vector<Polygon> pieces = streets.areas;
  for (const StreetLine& l : streets.lines)
    if (l.width > 0 && !l.points.empty())
      add_buffered(simplified(l.points), 0.5 * std::max(l.width, kMinWidth), pieces);
  if (pieces.empty()) return {};
  return detail::simplify_boundaries(union_polygons(pieces), kOutlineTolerance);
}

}  // namespace urbanpvs::geometry
