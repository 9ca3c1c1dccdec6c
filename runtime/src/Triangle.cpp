// SPDX-License-Identifier: MIT
#include <algorithm>

#include "urbanpvs/runtime/Types.hpp"

namespace urbanpvs::runtime {
namespace {

/// Twice the signed area of (a, b, p): > 0 when p is left of a → b.
double orient(const Point2& a, const Point2& b, double px, double py) noexcept {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

bool lex_less(const Point2& a, const Point2& b) noexcept {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}

/// orient() with the edge's endpoints in a canonical (lexicographic) order, sign-corrected.
/// Floating-point orient(a, b, p) and orient(b, a, p) may round differently; evaluating both
/// triangles of a shared edge with the same operand order gives them exactly opposite answers,
/// so no point on or near the edge falls into neither (no cracks between cells).
double edge_side(const Point2& a, const Point2& b, double px, double py) noexcept {
  return lex_less(b, a) ? -orient(b, a, px, py) : orient(a, b, px, py);
}

/// p is on the same side of edge a → b as the opposite vertex c, or on the edge.
bool on_inner_side(const Point2& a, const Point2& b, const Point2& c, double px,
                   double py) noexcept {
  const double side_c = edge_side(a, b, c.x, c.y);
  const double side_p = edge_side(a, b, px, py);
  return side_c > 0 ? side_p >= 0 : (side_c < 0 && side_p <= 0);  // side_c == 0: degenerate
}

}  // namespace

bool triangle_contains(const std::array<Point2, 3>& t, double x, double y) noexcept {
  // The box test first: cheap rejection, and it guarantees that a point accepted here lies in
  // the triangle's bounding box, which is what the point-location grid indexes.
  if (!(x >= std::min({t[0].x, t[1].x, t[2].x}) && x <= std::max({t[0].x, t[1].x, t[2].x}) &&
        y >= std::min({t[0].y, t[1].y, t[2].y}) && y <= std::max({t[0].y, t[1].y, t[2].y}))) {
    return false;
  }
  return on_inner_side(t[0], t[1], t[2], x, y) && on_inner_side(t[1], t[2], t[0], x, y) &&
         on_inner_side(t[2], t[0], t[1], x, y);
}

}  // namespace urbanpvs::runtime
